"""A bake's whole surface for the Python tests, through `walkrad inspect --mesh-json` (chunks are Draco)."""
import json
import os
import subprocess


def read_bake_mesh(walkrad, bake):
    """(positions, radiosity, indices): lists of xyz tuples, rgb tuples and vertex indices."""
    path = os.path.join(os.path.dirname(os.path.abspath(bake)), os.path.basename(bake) + "-mesh.json")
    subprocess.run([walkrad, "inspect", bake, "--mesh-json", path], check=True, stdout=subprocess.DEVNULL)
    with open(path) as f:
        m = json.load(f)
    triples = lambda a: [tuple(a[k:k + 3]) for k in range(0, len(a), 3)]
    return triples(m["positions"]), triples(m["radiosity"]), m["indices"]

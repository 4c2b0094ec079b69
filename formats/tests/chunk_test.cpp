// Chunks: what write_chunk writes, read_chunk reads back exactly; truncated files are refused.
#include "walkrad/formats/chunk.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "walkrad/formats/chunk_writer.h"
#include "walkrad/formats/error.h"

namespace walkrad {
namespace {

ChunkMesh two_triangles() {
  ChunkMesh m;
  m.positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  m.normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  m.colors = {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f, 0.7f, 0.8f, 0.9f, 1.0f, 1.5f, 2.0f};
  m.radiosity = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("walkrad-chunk-test-" + name)).string();
}

TEST(Chunk, RoundTripsExactly) {
  const std::string path = temp_path("roundtrip.glb");
  const ChunkMesh m = two_triangles();
  const uint64_t bytes = write_chunk(path, m);
  EXPECT_EQ(bytes, std::filesystem::file_size(path));
  const ChunkMesh back = read_chunk(path);
  EXPECT_EQ(back.positions, m.positions);
  EXPECT_EQ(back.normals, m.normals);
  EXPECT_EQ(back.colors, m.colors);
  EXPECT_EQ(back.radiosity, m.radiosity);
  EXPECT_EQ(back.indices, m.indices);
  std::filesystem::remove(path);
}

// A wavy grid with smooth colours and radiosity spanning a large range.
ChunkMesh grid_mesh(int n) {
  ChunkMesh m;
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) {
      const float u = float(x) / n, v = float(y) / n;
      m.positions.insert(m.positions.end(), {3 * u, 2 * v, 0.1f * std::sin(7 * u) * std::cos(5 * v)});
      m.normals.insert(m.normals.end(), {0, 0, 1});
      m.colors.insert(m.colors.end(), {u, v, 0.002f * u * v});  // dark values: sRGB is steepest there
      m.radiosity.insert(m.radiosity.end(), {40 * u * u, 3 * v, 0.01f + u * v});
    }
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const uint32_t a = uint32_t(y * (n + 1) + x), b = a + 1, c = a + uint32_t(n) + 2, d = a + uint32_t(n) + 1;
      m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
    }
  return m;
}

double srgb(double c) { return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055; }

// Draco: 5× smaller at least, and every decoded value within the stated error (vertices matched by
// position, since Draco reorders them).
TEST(Chunk, DracoDecodesWithinTheStatedErrorAndIsSmaller) {
  const ChunkMesh m = grid_mesh(64);
  const double position_tolerance = 1e-5 * length(m.bounds().diagonal()), radiosity_tolerance = 1e-3;
  const ChunkEncoding enc = draco_encoding(m.bounds(), position_tolerance, 40.0, radiosity_tolerance);
  EXPECT_LE(enc.position.max_error(), position_tolerance);
  EXPECT_LE(enc.radiosity.max_error(), radiosity_tolerance);
  const std::string plain = temp_path("plain.glb"), draco = temp_path("draco.glb");
  const uint64_t plain_bytes = write_chunk(plain, m), draco_bytes = write_chunk(draco, m, enc);
  EXPECT_GE(double(plain_bytes) / double(draco_bytes), 5.0) << plain_bytes << " / " << draco_bytes;
  const ChunkMesh back = read_chunk(draco);
  ASSERT_EQ(back.triangle_count(), m.triangle_count());
  ASSERT_EQ(back.vertex_count(), m.vertex_count());
  const int n = 64;
  for (size_t v = 0; v < back.vertex_count(); ++v) {
    // The grid vertex this one came from: x and y are quantised far finer than the grid's spacing.
    const int x = int(std::lround(back.positions[3 * v] / 3 * n)), y = int(std::lround(back.positions[3 * v + 1] / 2 * n));
    const size_t o = size_t(y * (n + 1) + x);
    for (int k = 0; k < 3; ++k) {
      EXPECT_LE(std::fabs(back.positions[3 * v + k] - m.positions[3 * o + k]), position_tolerance * 1.001);
      EXPECT_LE(std::fabs(srgb(back.colors[3 * v + k]) - srgb(m.colors[3 * o + k])), 0.5 / 255) << "vertex " << v;
      EXPECT_LE(std::fabs(back.radiosity[3 * v + k] - m.radiosity[3 * o + k]), radiosity_tolerance * 1.001);
    }
  }
  std::filesystem::remove(plain);
  std::filesystem::remove(draco);
}

TEST(Chunk, WritingIsDeterministic) {
  const std::string a = temp_path("a.glb"), b = temp_path("b.glb");
  write_chunk(a, two_triangles());
  write_chunk(b, two_triangles());
  std::ifstream fa(a, std::ios::binary), fb(b, std::ios::binary);
  const std::string sa((std::istreambuf_iterator<char>(fa)), {}), sb((std::istreambuf_iterator<char>(fb)), {});
  EXPECT_EQ(sa, sb);
  std::filesystem::remove(a);
  std::filesystem::remove(b);
}

// Every strict prefix of a valid .glb is refused with an InputError naming the file, never a crash.
TEST(Chunk, RefusesEveryTruncation) {
  const std::string path = temp_path("whole.glb"), cut = temp_path("cut.glb");
  write_chunk(path, two_triangles());
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), {});
  for (size_t n = 0; n < bytes.size(); ++n) {
    std::ofstream(cut, std::ios::binary | std::ios::trunc).write(bytes.data(), std::streamsize(n));
    try {
      read_chunk(cut);
      ADD_FAILURE() << "accepted a prefix of " << n << " bytes";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), cut);
    }
  }
  std::filesystem::remove(path);
  std::filesystem::remove(cut);
}

}  // namespace
}  // namespace walkrad

namespace walkrad {
namespace {

// A Draco-compressed chunk (KHR_draco_mesh_compression, written by tests/fuzz/make_draco_seed.cpp):
// decoded to the same quad as the plain one, corner for corner.
TEST(Chunk, DecodesDraco) {
  const ChunkMesh m = read_chunk(std::string(WALKRAD_SOURCE_DIR) + "/tests/fuzz/corpus/chunk/quad-draco.glb");
  ASSERT_EQ(m.vertex_count(), 4u);
  ASSERT_EQ(m.triangle_count(), 2u);
  const Bounds b = m.bounds();
  EXPECT_EQ(b.lo, Vec3(0, 0, 0));
  EXPECT_EQ(b.hi, Vec3(1, 1, 0));
  double area = 0;
  for (size_t t = 0; t < 2; ++t) {
    Vec3 v[3];
    for (int k = 0; k < 3; ++k) {
      const uint32_t i = m.indices[t * 3 + k];
      v[k] = Vec3(m.positions[i * 3], m.positions[i * 3 + 1], m.positions[i * 3 + 2]);
      EXPECT_EQ(m.normals[i * 3 + 2], 1.0f);
      // The seed's colours: red, green, blue, white at corners (0,0), (1,0), (1,1), (0,1).
      const float expected[4][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
      const int corner = v[k].y < 0.5 ? (v[k].x < 0.5 ? 0 : 1) : (v[k].x > 0.5 ? 2 : 3);
      for (int c = 0; c < 3; ++c) EXPECT_EQ(m.colors[i * 3 + c], expected[corner][c]);
    }
    area += 0.5 * length(cross(v[1] - v[0], v[2] - v[0]));
    EXPECT_GT(cross(v[1] - v[0], v[2] - v[0]).z, 0);  // counter-clockwise seen from +z
  }
  EXPECT_DOUBLE_EQ(area, 1.0);
}

}  // namespace
}  // namespace walkrad

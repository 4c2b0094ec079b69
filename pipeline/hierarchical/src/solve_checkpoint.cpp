// The solve's state between two refinement rounds, to bytes and back, so that a bake of hours
// resumes from its last complete round. Everything a round changes is saved: the hierarchy (nodes,
// links, children, view hits), the solver's per-node measures and the statistics so far. What the
// constructor derives from the scene alone is rebuilt by it, identically, and not saved. A link's
// random numbers are seeded by its two nodes, so the rounds after a resume draw what they would have.
#include <type_traits>

#include "solver.h"

namespace walkrad {

static_assert(std::is_trivially_copyable_v<HNodeValues> && std::is_trivially_copyable_v<Link>);
static_assert(std::is_trivially_copyable_v<IterationStats> && std::is_trivially_copyable_v<ViewHit>);

void Hierarchy::save_state(ByteWriter& out) const {
  out.put(uint64_t(nodes_.size()));
  for (const HNode& n : nodes_) {
    out.put(static_cast<const HNodeValues&>(n));
    out.put_vector(n.links);
  }
  out.put_vector(children_);
  out.put_vector(hits_);
  out.put(uint64_t(element_count_));
}

void Hierarchy::load_state(ByteReader& in) {
  const auto count = in.get<uint64_t>();
  // The clusters and the input polygons' roots come first and never move: a state from another
  // scene or tree shows itself here.
  if (count < nodes_.size()) throw ByteFormatError("the saved hierarchy is smaller than the scene's");
  if (count > in.remaining() / sizeof(HNodeValues)) throw ByteFormatError("truncated (the nodes run past the end)");
  HNodes nodes(count);
  for (size_t i = 0; i < count; ++i) {
    static_cast<HNodeValues&>(nodes[i]) = in.get<HNodeValues>();
    in.get_vector(nodes[i].links);
    if (i < nodes_.size() && (nodes[i].cluster != nodes_[i].cluster || nodes[i].polygon != nodes_[i].polygon))
      throw ByteFormatError("the saved hierarchy does not match the scene's");
  }
  nodes_ = std::move(nodes);
  in.get_vector(children_);
  in.get_vector(hits_);
  element_count_ = size_t(in.get<uint64_t>());
}

namespace hierarchical_detail {

namespace {

// HierarchicalStats field by field (its oracle is a string). A field added to it must be added here:
// the size check below fails until it is.
static_assert(sizeof(HierarchicalStats) == 232 + sizeof(std::vector<IterationStats>) + sizeof(std::string),
              "HierarchicalStats changed: save and load the new field in solve_checkpoint.cpp");

template <class Io, class Stats>
void each_stat(Io&& io, Stats& s) {
  io(s.links), io(s.rays), io(s.unoccluded_links), io(s.monte_carlo_links), io(s.refinements), io(s.receiver_splits);
  io(s.recast), io(s.converged), io(s.white), io(s.min_area), io(s.above_tolerance), io(s.corrections);
  io(s.light_rays), io(s.light_refinements), io(s.balance_iterations), io(s.mean_row_sum), io(s.balance_row_error);
  io(s.balance_column_error), io(s.balance_unbalanced), io(s.exact_links), io(s.volume_links), io(s.grid_segments);
  io(s.link_bytes_peak), io(s.divided), io(s.probed_pairs), io(s.probe_hidden), io(s.probe_rays);
  io(s.proven_hidden), io(s.stalled_round);
}

}  // namespace

void Solver::save_state(ByteWriter& out, const RoundState& round) const {
  out.put(round);
  h_.save_state(out);
  const OracleState& o = oracle_.state();
  const SweepState& sw = sweeps_.state();
  out.put(sw.change), out.put(o.white), out.put(o.direct_weights);
  out.put_vector(o.variation), out.put_vector(o.left), out.put_vector(o.spread), out.put_vector(o.emitted);
  out.put_vector(o.weight), out.put_vector(sw.cube);
  out.put_vector(stats_.iterations);
  out.put_string(stats_.oracle);
  each_stat([&](const auto& v) { out.put(v); }, stats_);
}

Solver::RoundState Solver::load_state(ByteReader& in) {
  const auto round = in.get<RoundState>();
  h_.load_state(in);
  OracleState& o = oracle_.state();
  SweepState& sw = sweeps_.state();
  sw.change = in.get<double>(), o.white = in.get<double>(), o.direct_weights = in.get<bool>();
  in.get_vector(o.variation), in.get_vector(o.left), in.get_vector(o.spread), in.get_vector(o.emitted);
  in.get_vector(o.weight), in.get_vector(sw.cube);
  in.get_vector(stats_.iterations);
  stats_.oracle = in.get_string();
  each_stat([&](auto& v) { v = in.get<std::remove_reference_t<decltype(v)>>(); }, stats_);
  if (!in.done()) throw ByteFormatError("bytes past the end of the saved state");
  // Consumed by the first rounds (refine_for_lights): a state saved after them no longer needs it.
  if (round.next_round > 1) refinement_.forget_light_frontier();
  return round;
}

}  // namespace hierarchical_detail
}  // namespace walkrad

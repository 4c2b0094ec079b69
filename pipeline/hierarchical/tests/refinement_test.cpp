// The refinement on its own (refinement.h): what it decides for a pair from the geometry, what it plans
// for a receiver from the oracle's measures, the links it asks for, and the property every hierarchy
// of links must have (Hanrahan, Salzman & Aupperle 1991): each pair of facing surfaces exchanges light
// through exactly one link, at whatever level, and no pair through two.
#include <memory>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "refinement.h"
#include "polygon_scene.h"
#include "walkrad/testing/howell_catalogue.h"
#include "walkrad/testing/test_scenes.h"

namespace walkrad::hierarchical_detail {
namespace {

// A scene of the given polygons (polygon_scene.h) with its refinement; the oracle as it stands before any
// solve (no white: nothing is worth splitting for what it carries).
struct RefinementScene : test::PolygonScene {
  HierarchicalStats stats;
  std::unique_ptr<ErrorOracle> oracle;
  std::unique_ptr<Refinement> refinement;

  explicit RefinementScene(std::vector<Polygon> polygons)
      : PolygonScene(std::move(polygons)), oracle(std::make_unique<ErrorOracle>(*h, settings, 1e-4)),
        refinement(std::make_unique<Refinement>(*h, *rays, settings, stats, *oracle, Division{}, default_min_area(*h))) {}
  Refinement::PairOutcome decide(uint32_t i, uint32_t j) const {
    Refinement::PairTask t{i, j};
    return refinement->decide_pair(t);
  }
  // Whether node a is node n or one of its ancestors.
  bool above(uint32_t a, uint32_t n) const {
    for (int32_t k = int32_t(n); k >= 0; k = (*h)[uint32_t(k)].parent)
      if (uint32_t(k) == a) return true;
    return false;
  }
};

// The C-11 squares a metre apart (the first facing +y, the second −y).
std::vector<Polygon> facing_squares() {
  const test::RectanglePair pair = test::parallel_rectangles(1.0, 1.0, 1.0);
  return {pair.first, pair.second};
}

Polygon reversed(Polygon p) {
  std::swap(p.v[1], p.v[3]);
  return p;
}

TEST(Refinement, DecidesAPairFromTheGeometryAlone) {
  {
    const RefinementScene s(facing_squares());
    EXPECT_EQ(s.decide(s.root(0), s.root(0)).kind, Refinement::PairKind::kDrop) << "a planar element sees itself";
    EXPECT_EQ(s.decide(s.h->root(), s.h->root()).kind, Refinement::PairKind::kSelf) << "a cluster's self-pair opens";
    // Nothing is worth splitting before the white is known: the pair is linked, with the default rays,
    // and none needs casting where nothing lies between.
    const Refinement::PairOutcome link = s.decide(s.root(0), s.root(1));
    EXPECT_EQ(link.kind, Refinement::PairKind::kLink);
    EXPECT_EQ(link.samples, s.settings.rays);
    EXPECT_FALSE(link.need_rays);
  }
  {
    // The second square turned to face away: every point of it lies on the plane's far side.
    const test::RectanglePair pair = test::parallel_rectangles(1.0, 1.0, 1.0);
    const RefinementScene s({pair.first, reversed(pair.second)});
    EXPECT_EQ(s.decide(s.root(0), s.root(1)).kind, Refinement::PairKind::kDrop);
    EXPECT_EQ(s.decide(s.root(1), s.root(0)).kind, Refinement::PairKind::kDrop);
  }
  {
    // A wall between them, wider than both: the link must cast rays.
    std::vector<Polygon> polygons = facing_squares();
    polygons.push_back(test::rect(1, 0.5, -1.0, 2.0, -1.0, 2.0, +1));
    const RefinementScene s(polygons);
    const Refinement::PairOutcome link = s.decide(s.root(0), s.root(1));
    EXPECT_EQ(link.kind, Refinement::PairKind::kLink);
    EXPECT_TRUE(link.need_rays);
  }
}

TEST(Refinement, AReceiverWhoseLightVariesTakesEveryLinkDown) {
  RefinementScene s(facing_squares());
  HNode& lower = (*s.h)[s.root(0)];
  (*s.h)[s.root(1)].B = (*s.h)[s.root(1)].Bt = Vec3(1, 1, 1);
  lower.B = lower.Bt = Vec3(0.5, 0.5, 0.5);
  Link l;
  l.F = float(test::howell_c11(1.0, 1.0, 1.0));
  l.source = s.root(1);
  lower.links = {l, l};
  s.oracle->update_scales();
  s.oracle->measure_variation();
  // Even shares (1 each): an even transfer, and a uniform source in full view is exact however much it carries.
  const Refinement::ReceiverPlan kept = s.refinement->plan_receiver(s.root(0));
  EXPECT_FALSE(kept.split_receiver);
  EXPECT_EQ(kept.action, (std::vector<Refinement::LinkAction>{Refinement::kKeep, Refinement::kKeep}));
  // Its children would differ by ten times its tolerance: every link goes down to them.
  s.oracle->state().variation[s.root(0)] = float(10 * s.oracle->tolerance(s.root(0)));
  const Refinement::ReceiverPlan split = s.refinement->plan_receiver(s.root(0));
  EXPECT_TRUE(split.split_receiver);
  EXPECT_EQ(split.action, (std::vector<Refinement::LinkAction>{Refinement::kSplit, Refinement::kSplit}));
  EXPECT_EQ(split.candidates.size(), 2u);
  // Applied: the receiver's four children each ask for a link to the source, and it keeps none.
  s.refinement->refine_existing();  // (the split may move the node list: lower is not read again)
  const HNode& after = (*s.h)[s.root(0)];
  ASSERT_EQ(after.child_count, 4);
  EXPECT_TRUE(after.links.empty());
  const std::vector<LinkRequest> requests = s.refinement->take_requests();
  ASSERT_EQ(requests.size(), 8u);
  for (const LinkRequest& r : requests) {
    EXPECT_EQ((*s.h)[r.receiver].parent, int32_t(s.root(0)));
    EXPECT_EQ(r.source, s.root(1));
  }
  EXPECT_EQ(s.refinement->new_link_count(), 0u) << "the requests are handed over once";
}

TEST(Refinement, AWhollyHiddenLinkIsCastAgainBeforeItIsRefined) {
  RefinementScene s(facing_squares());
  for (uint32_t k : {s.root(0), s.root(1)}) (*s.h)[k].B = (*s.h)[k].Bt = Vec3(1, 1, 1);
  Link hidden;
  hidden.source = s.root(1);
  hidden.F = 0;
  hidden.sigma = 0.5f;  // every ray blocked, and what they could have missed matters
  hidden.rays = 1;
  hidden.samples = uint16_t(s.settings.rays);
  (*s.h)[s.root(0)].links = {hidden};
  s.oracle->update_scales();
  s.oracle->measure_variation();
  EXPECT_EQ(s.refinement->plan_receiver(s.root(0)).action[0], Refinement::kRecast);
  // Cast again with kHiddenRecast times the rays and still dark: refined while it may matter.
  (*s.h)[s.root(0)].links[0].samples = uint16_t(Refinement::kHiddenRecast * s.settings.rays);
  EXPECT_EQ(s.refinement->plan_receiver(s.root(0)).action[0], Refinement::kSplit);
  // Once what it could carry no longer matters, kept at 0 with its σ.
  (*s.h)[s.root(0)].links[0].sigma = 1e-9f;
  EXPECT_EQ(s.refinement->plan_receiver(s.root(0)).action[0], Refinement::kKeep);
}

// The first refinement of a closed box: Hanrahan et al.'s property, each facing pair of faces linked
// exactly once (a link covers the pairs of the leaves below its two ends), and the same nodes and links
// whatever the thread count.
std::vector<LinkRequest> first_links(int threads, size_t& nodes) {
  tbb::global_control control(tbb::global_control::max_allowed_parallelism, size_t(threads));
  Scene box = test::closed_box(1.0, {0.5, 0.5, 0.5}, {0, 0, 0});
  RefinementScene s(box.polygons);
  s.refinement->refine_first();
  std::vector<LinkRequest> requests = s.refinement->take_requests();
  nodes = s.h->nodes().size();
  const size_t faces = box.polygons.size();
  for (uint32_t p = 0; p < faces; ++p)
    for (uint32_t q = 0; q < faces; ++q) {
      int covering = 0;
      for (const LinkRequest& r : requests) covering += s.above(r.receiver, s.root(p)) && s.above(r.source, s.root(q));
      EXPECT_EQ(covering, p == q ? 0 : 1) << "face " << p << " from face " << q;
    }
  return requests;
}

TEST(Refinement, LinksEachFacingPairOnceWhateverTheThreadCount) {
  size_t nodes_one = 0, nodes_two = 0;
  const std::vector<LinkRequest> one = first_links(1, nodes_one), two = first_links(2, nodes_two);
  EXPECT_EQ(nodes_one, nodes_two);
  ASSERT_EQ(one.size(), two.size());
  for (size_t k = 0; k < one.size(); ++k) {
    EXPECT_EQ(one[k].receiver, two[k].receiver);
    EXPECT_EQ(one[k].source, two[k].source);
    EXPECT_EQ(one[k].samples, two[k].samples);
  }
}

}  // namespace
}  // namespace walkrad::hierarchical_detail

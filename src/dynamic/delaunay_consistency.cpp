#include "ply_slam/dynamic/delaunay_consistency.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <opencv2/imgproc.hpp>
#include <random>
#include <set>

#include "ply_slam/common/rigid_alignment.h"
#include "ply_slam/common/statistics.h"

namespace ply_slam {
namespace {

// Up to `rounds` different triples of distinct indices below n, drawn at random with a seed
// fixed by n (runs repeat); all of them when there are no more. A triple with a repeated index
// would leave a motion undetermined.
std::vector<std::array<size_t, 3>> distinctTriples(size_t n, int rounds) {
  const size_t all = n * (n - 1) * (n - 2) / 6;
  const size_t wanted = std::min(all, static_cast<size_t>(rounds));
  std::mt19937 random(static_cast<unsigned>(n));
  std::uniform_int_distribution<size_t> pick(0, n - 1);
  std::set<std::array<size_t, 3>> drawn;
  std::vector<std::array<size_t, 3>> triples;
  while (triples.size() < wanted) {
    std::array<size_t, 3> t{pick(random), pick(random), pick(random)};
    std::sort(t.begin(), t.end());
    if (t[0] == t[1] || t[1] == t[2] || !drawn.insert(t).second) continue;
    triples.push_back(t);
  }
  return triples;
}

}  // namespace

Eigen::Isometry3d DelaunayConsistency::rigidMotion(
    const std::vector<FeatureCorrespondence>& features, const std::vector<bool>& use) const {
  std::vector<Eigen::Vector3d> from, to;
  for (size_t i = 0; i < features.size(); ++i)
    if (use[i]) {
      from.push_back(features[i].previous);
      to.push_back(features[i].current);
    }
  return from.size() >= 3 ? alignRigid(from, to) : Eigen::Isometry3d::Identity();
}

DelaunayConsistency::Change DelaunayConsistency::residual(const FeatureCorrespondence& f,
                                                          const Eigen::Isometry3d& motion) const {
  const Eigen::Vector3d r = motion * f.previous - f.current;
  const double norm = r.norm();
  if (norm < 1e-12) return {0.0, 0.0};
  const Eigen::Vector3d d = r / norm;
  // The residual's variance along itself: both measurements' noise.
  const double variance =
      noise_.varianceAlong(f.current, d, f.slope_current) +
      noise_.varianceAlong(f.previous, motion.linear().transpose() * d, f.slope_previous);
  return {norm, norm / std::sqrt(variance)};
}

DelaunayConsistency::Change DelaunayConsistency::edgeChange(const FeatureCorrespondence& a,
                                                            const FeatureCorrespondence& b) const {
  const Eigen::Vector3d edge_before = a.previous - b.previous, edge_after = a.current - b.current;
  const double before = edge_before.norm();
  const double after = edge_after.norm();
  if (before < 1e-9 || after < 1e-9) return {0.0, 0.0};
  // The length's variance: both endpoints' noise along the edge, in both frames.
  const Eigen::Vector3d d0 = edge_before / before, d1 = edge_after / after;
  const double variance = noise_.varianceAlong(a.previous, d0, a.slope_previous) +
                          noise_.varianceAlong(b.previous, d0, b.slope_previous) +
                          noise_.varianceAlong(a.current, d1, a.slope_current) +
                          noise_.varianceAlong(b.current, d1, b.slope_current);
  return {std::abs(after - before), std::abs(after - before) / std::sqrt(variance)};
}

bool DelaunayConsistency::exceeds(const Change& change, double scale) const {
  return change.metres > params_.min_change && change.sigmas > params_.sigma_factor * scale;
}

double DelaunayConsistency::noiseScale(const std::vector<double>& sigmas, double median_of_unit) {
  return sigmas.empty() ? 1.0 : std::max(1.0, upperMedian(sigmas) / median_of_unit);
}

std::vector<double> DelaunayConsistency::weights(const std::vector<FeatureCorrespondence>& features,
                                                 int width, int height, const StaticPrior& prior,
                                                 std::optional<StaticFit>* static_fit) const {
  std::vector<double> weight(features.size(), 0.0);
  if (features.size() < 3) return weight;
  const EdgeGraph graph = buildGraph(features, width, height);
  const Bodies bodies = growBodies(graph);
  const std::vector<bool> seeds = staticSeeds(features, bodies, prior);
  if (seeds.empty()) {
    // Too small a body to fix the camera's motion by: the edges' votes, and the features of a
    // clearly smaller body than the largest moved.
    const size_t largest =
        bodies.size.empty() ? 0 : *std::max_element(bodies.size.begin(), bodies.size.end());
    for (size_t i = 0; i < features.size(); ++i)
      if (graph.edges_of[i] > 0)
        weight[i] = static_cast<double>(graph.bad_of[i]) / graph.edges_of[i];
    for (size_t i = 0; i < features.size(); ++i)
      if (bodies.of[i] >= 0 && bodies.size[bodies.of[i]] < params_.minority_share * largest)
        weight[i] = 1.0;
    return weight;
  }
  StaticFit fit;
  const std::vector<bool> inlier = carriedByStaticMotion(features, seeds, fit);
  if (static_fit) *static_fit = fit;
  // Now the moved end of a broken edge is known: the edge blames it alone.
  for (size_t i = 0; i < features.size(); ++i) {
    if (graph.edges_of[i] == 0) continue;
    if (!inlier[i]) {
      weight[i] = 1.0;
      continue;
    }
    int edges = 0, broken = 0;
    for (const auto& [j, ok] : graph.neighbours[i])
      if (inlier[j]) {
        ++edges;
        broken += !ok;
      }
    weight[i] = edges > 0 ? static_cast<double>(broken) / edges : 0.0;
  }
  return weight;
}

DelaunayConsistency::EdgeGraph DelaunayConsistency::buildGraph(
    const std::vector<FeatureCorrespondence>& features, int width, int height) const {
  // Subdiv2D reports edges by position: map positions back to features (a duplicate
  // position keeps the first feature).
  cv::Subdiv2D subdiv(cv::Rect(-1, -1, width + 2, height + 2));
  std::map<std::pair<float, float>, size_t> at;
  for (size_t i = 0; i < features.size(); ++i) {
    const cv::Point2f p(static_cast<float>(features[i].pixel.x()),
                        static_cast<float>(features[i].pixel.y()));
    if (p.x < -1 || p.y < -1 || p.x >= width + 1 || p.y >= height + 1) continue;
    if (!at.emplace(std::make_pair(p.x, p.y), i).second) continue;
    subdiv.insert(p);
  }
  EdgeGraph g;
  g.edges_of.assign(features.size(), 0);
  g.bad_of.assign(features.size(), 0);
  g.neighbours.resize(features.size());
  std::vector<cv::Vec4f> edge_list;
  subdiv.getEdgeList(edge_list);
  // Edges to the outer virtual vertices find no feature and are skipped.
  std::vector<std::pair<size_t, size_t>> edges;
  std::vector<Change> changes;
  std::vector<double> sigmas;
  for (const auto& e : edge_list) {
    const auto a = at.find({e[0], e[1]}), b = at.find({e[2], e[3]});
    if (a == at.end() || b == at.end()) continue;
    edges.push_back({a->second, b->second});
    changes.push_back(edgeChange(features[a->second], features[b->second]));
    sigmas.push_back(changes.back().sigmas);
  }
  // Most edges are static: where they change more than the model says (motion blur, rolling
  // shutter, matching at speed), the model's noise is scaled up to theirs.
  const double edge_scale = noiseScale(sigmas, 0.6745);  // median |N(0, 1)|
  for (size_t k = 0; k < edges.size(); ++k) {
    const auto [ia, ib] = edges[k];
    // A broken edge says one of its ends moved, not which: both get the vote.
    const bool bad = exceeds(changes[k], edge_scale);
    for (size_t f : {ia, ib}) {
      ++g.edges_of[f];
      g.bad_of[f] += bad;
    }
    g.neighbours[ia].push_back({ib, !bad});
    g.neighbours[ib].push_back({ia, !bad});
  }
  return g;
}

DelaunayConsistency::Bodies DelaunayConsistency::growBodies(const EdgeGraph& g) const {
  // A body moving as a whole keeps its inner edges: only its rim votes. So the features are
  // grown into rigid bodies: a feature joins a body when more of its edges into the body are
  // consistent than broken (a single edge across the motion keeps its length by chance).
  const size_t n = g.edges_of.size();
  Bodies bodies;
  bodies.of.assign(n, -1);
  std::vector<size_t> seeds;
  for (size_t i = 0; i < n; ++i)
    if (g.edges_of[i] > 0) seeds.push_back(i);
  std::stable_sort(seeds.begin(), seeds.end(), [&](size_t x, size_t y) {
    return g.edges_of[x] - g.bad_of[x] > g.edges_of[y] - g.bad_of[y];
  });
  for (size_t seed : seeds) {
    if (bodies.of[seed] >= 0) continue;
    const int id = static_cast<int>(bodies.size.size());
    bodies.of[seed] = id;
    size_t size = 1;
    std::vector<size_t> candidates;
    for (const auto& [j, ok] : g.neighbours[seed])
      if (ok) candidates.push_back(j);
    while (!candidates.empty()) {
      const size_t c = candidates.back();
      candidates.pop_back();
      if (bodies.of[c] >= 0) continue;
      int consistent = 0, broken = 0;
      for (const auto& [j, ok] : g.neighbours[c])
        if (bodies.of[j] == id) ++(ok ? consistent : broken);
      if (consistent <= broken) continue;  // looked at again when another neighbour joins
      bodies.of[c] = id;
      ++size;
      for (const auto& [j, ok] : g.neighbours[c])
        if (bodies.of[j] < 0) candidates.push_back(j);
    }
    bodies.size.push_back(size);
  }
  return bodies;
}

std::vector<bool> DelaunayConsistency::staticSeeds(
    const std::vector<FeatureCorrespondence>& features, const Bodies& bodies,
    const StaticPrior& prior) const {
  // Which features are the static scene to start from. A person a metre away covers half
  // the image, and a torso is rigid too: with the people in view most of the edges, the body
  // grown over the consistent ones joins people and background, or is a person. So, first:
  // the features the camera's predicted motion carries onto where they are now (a walker
  // moves 5-15 cm over the baseline, the prediction errs by a few cm); then those off
  // instances of moving classes; and only then the largest body.
  const size_t n = features.size();
  std::vector<bool> seed(n, false);
  if (prior.predicted_motion) {
    size_t count = 0;
    for (size_t i = 0; i < n; ++i) {
      const Change r = residual(features[i], *prior.predicted_motion);
      seed[i] = r.metres <= params_.prediction_tolerance;
      count += seed[i];
    }
    if (count >= kMinSeeds) return seed;
  }
  const auto largest = std::max_element(bodies.size.begin(), bodies.size.end());
  if (largest == bodies.size.end() || *largest < 3) return {};
  const int body = static_cast<int>(largest - bodies.size.begin());
  size_t count = 0;
  for (size_t i = 0; i < n; ++i) {
    seed[i] = bodies.of[i] == body && !(prior.on_moving_class && (*prior.on_moving_class)[i]);
    count += seed[i];
  }
  if (count >= kMinSeeds) return seed;
  for (size_t i = 0; i < n; ++i) seed[i] = bodies.of[i] == body;
  return seed;
}

std::vector<bool> DelaunayConsistency::carriedByStaticMotion(
    const std::vector<FeatureCorrespondence>& features, std::vector<bool> inlier,
    StaticFit& fit) const {
  // Distances along one edge are blind to motion across it, and long edges in depth are
  // noisy. The static features fix the camera's motion between the frames: every feature that
  // this motion does not carry onto its current position, beyond its noise, moved (this
  // replaces the edge votes of every feature with an edge).
  for (int round = 0; round < 2; ++round) {
    const Eigen::Isometry3d motion = rigidMotion(features, inlier);
    std::vector<Change> residuals;
    std::vector<double> static_sigmas;
    for (size_t i = 0; i < features.size(); ++i) {
      residuals.push_back(residual(features[i], motion));
      if (inlier[i]) static_sigmas.push_back(residuals.back().sigmas);
    }
    const double scale = noiseScale(static_sigmas, 1.5382);  // median of a 3-DoF chi
    for (size_t i = 0; i < features.size(); ++i) inlier[i] = !exceeds(residuals[i], scale);
    fit = {motion, scale, static_cast<size_t>(std::count(inlier.begin(), inlier.end(), true))};
  }
  return inlier;
}

bool DelaunayConsistency::movedApart(const std::vector<FeatureCorrespondence>& body,
                                     const StaticFit& fit) const {
  if (body.size() < 3) return false;
  std::vector<bool> best;
  size_t best_count = 0;
  for (const std::array<size_t, 3>& triple : distinctTriples(body.size(), kBodyRansacRounds)) {
    std::vector<bool> use(body.size(), false);
    for (size_t k : triple) use[k] = true;
    const Eigen::Isometry3d own = rigidMotion(body, use);
    std::vector<bool> follows(body.size());
    size_t count = 0;
    for (size_t i = 0; i < body.size(); ++i) {
      follows[i] = !exceeds(residual(body[i], own), fit.noise_scale);
      count += follows[i];
    }
    if (count > best_count) {
      best = std::move(follows);
      best_count = count;
    }
  }
  if (best_count < 3 || 2 * best_count < body.size()) return false;
  const Eigen::Isometry3d own = rigidMotion(body, best);
  FeatureCorrespondence centre{Eigen::Vector2d::Zero(), Eigen::Vector3d::Zero(),
                               Eigen::Vector3d::Zero()};
  for (size_t i = 0; i < body.size(); ++i)
    if (best[i]) centre.previous += body[i].previous / static_cast<double>(best_count);
  centre.current = own * centre.previous;
  return exceeds(residual(centre, fit.motion), fit.noise_scale);
}

}  // namespace ply_slam

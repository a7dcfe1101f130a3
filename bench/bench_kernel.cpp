// ns per pair for each stage of the contact pipeline, on random realistic pairs:
// semi-axes in ratio 1 : 1.4 : 1.96, random orientations, overlaps ~1e-3 of the size.
// All inputs are built before the timed loops.
#include "ellipsoid_kernel.h"

#include <benchmark/benchmark.h>

#include <random>
#include <vector>

using namespace EllipsoidDep;

namespace {

constexpr int kPairs = 1024;

struct Pair {
  Ellipsoid a, b;
  Vec3 n;    // converged contact normal (or separating direction)
};

Mat3 rotation(std::mt19937_64 &rng)
{
  std::normal_distribution<double> g;
  const double q[4] = {g(rng), g(rng), g(rng), g(rng)};
  return make_ellipsoid(Vec3::Zero(), q, Vec3(1, 1, 1)).rotation;
}

// B touching A along a random common normal n with d(n) = delta
std::vector<Pair> make_pairs(double delta_rel, bool spheres, unsigned seed)
{
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0.8, 1.2);
  std::vector<Pair> out;
  for (int i = 0; i < kPairs; ++i) {
    const double sa = u(rng), sb = u(rng);
    const Vec3 axa = spheres ? Vec3(sa, sa, sa) : Vec3(sa, 1.4 * sa, 1.96 * sa);
    const Vec3 axb = spheres ? Vec3(sb, sb, sb) : Vec3(sb, 1.4 * sb, 1.96 * sb);
    Pair p;
    p.a = make_ellipsoid(Vec3(g(rng), g(rng), g(rng)), rotation(rng), axa);
    p.n = Vec3(g(rng), g(rng), g(rng)).normalized();
    const Ellipsoid b0 = make_ellipsoid(Vec3::Zero(), rotation(rng), axb);
    const Vec3 pa =
        p.a.center + p.a.inverse_form * p.n / std::sqrt(p.n.dot(p.a.inverse_form * p.n));
    const Vec3 cb = pa - delta_rel * std::min(sa, sb) * p.n +
        b0.inverse_form * p.n / std::sqrt(p.n.dot(b0.inverse_form * p.n));
    p.b = make_ellipsoid(cb, b0.rotation, axb);
    out.push_back(p);
  }
  return out;
}

const std::vector<Pair> &overlapping()
{
  static const auto v = make_pairs(1e-3, false, 1);
  return v;
}
const std::vector<Pair> &disjoint()
{
  static const auto v = make_pairs(-0.05, false, 2);
  return v;
}

// Times f(k) for k cycling over the kPairs prepared inputs.
template <class F> void cycle(benchmark::State &state, F &&f)
{
  int k = 0;
  for (auto _ : state) {
    f(k);
    k = (k + 1) & (kPairs - 1);
  }
}

void BM_BoundingReject(benchmark::State &state)
{
  auto pairs = disjoint();
  for (auto &p : pairs)    // far apart
    p.b = make_ellipsoid(p.a.center + 10.0 * p.n, p.b.rotation, p.b.semi_axes);
  std::vector<double> cache(PairHistory::PIPELINE_SIZE * kPairs, 0.0);
  PipelineSettings ps;
  PipelineCounters cnt;
  cycle(state, [&](int k) {
    auto g = evaluate_pair(pairs[k].a, pairs[k].b, ps, &cache[PairHistory::PIPELINE_SIZE * k], cnt);
    benchmark::DoNotOptimize(g);
  });
}
BENCHMARK(BM_BoundingReject);

void BM_PlaneSeparates(benchmark::State &state)
{
  const auto &pairs = disjoint();
  std::vector<SeparatingPlane> planes(kPairs);
  for (int i = 0; i < kPairs; ++i) build_separating_plane(pairs[i].a, pairs[i].b, planes[i]);
  cycle(state, [&](int k) {
    bool s = plane_separates(planes[k], pairs[k].a, pairs[k].b);
    benchmark::DoNotOptimize(s);
  });
}
BENCHMARK(BM_PlaneSeparates);

// The whole evaluate_pair call in its steady state: one untimed pass fills each pair's cache
// (a plane for disjoint pairs, a normal for contacts), then the same pairs are timed.
PipelineCounters time_pipeline(benchmark::State &state, const std::vector<Pair> &pairs)
{
  std::vector<double> cache(PairHistory::PIPELINE_SIZE * kPairs, 0.0);
  PipelineSettings ps;
  PipelineCounters cnt;
  for (int i = 0; i < kPairs; ++i)
    evaluate_pair(pairs[i].a, pairs[i].b, ps, &cache[PairHistory::PIPELINE_SIZE * i], cnt);
  cycle(state, [&](int k) {
    auto g = evaluate_pair(pairs[k].a, pairs[k].b, ps, &cache[PairHistory::PIPELINE_SIZE * k], cnt);
    benchmark::DoNotOptimize(g);
  });
  cnt.pairs -= kPairs;    // count the timed evaluations only
  return cnt;
}

// the cached plane still separates
void BM_PipelineCachedPlane(benchmark::State &state)
{
  const PipelineCounters cnt = time_pipeline(state, disjoint());
  state.counters["hit_fraction"] = double(cnt.plane_hits) / double(cnt.pairs);
}
BENCHMARK(BM_PipelineCachedPlane);

void BM_WangDecision(benchmark::State &state)
{
  const auto &pairs = overlapping();
  ContactSettings st;
  cycle(state, [&](int k) {
    auto s = wang_classify(pairs[k].a, pairs[k].b, st);
    benchmark::DoNotOptimize(s);
  });
}
BENCHMARK(BM_WangDecision);

void BM_WangDecisionDisjoint(benchmark::State &state)
{
  const auto &pairs = disjoint();
  ContactSettings st;
  cycle(state, [&](int k) {
    auto s = wang_classify(pairs[k].a, pairs[k].b, st);
    benchmark::DoNotOptimize(s);
  });
}
BENCHMARK(BM_WangDecisionDisjoint);

void BM_PlaneConstruction(benchmark::State &state)
{
  const auto &pairs = disjoint();
  cycle(state, [&](int k) {
    SeparatingPlane pl;
    bool ok = build_separating_plane(pairs[k].a, pairs[k].b, pl);
    benchmark::DoNotOptimize(ok);
    benchmark::DoNotOptimize(pl);
  });
}
BENCHMARK(BM_PlaneConstruction);

// warm start: last step's normal, off by ~1e-4 rad (a DEM step's rotation)
void BM_WarmContact(benchmark::State &state)
{
  const auto &pairs = overlapping();
  std::mt19937_64 rng(9);
  std::normal_distribution<double> g;
  std::vector<Vec3> warm(kPairs);
  for (int i = 0; i < kPairs; ++i)
    warm[i] = (pairs[i].n + 1e-4 * Vec3(g(rng), g(rng), g(rng))).normalized();
  ContactSettings st;
  long long iters = 0, n = 0;
  cycle(state, [&](int k) {
    auto c = ellipsoid_contact(pairs[k].a, pairs[k].b, st, &warm[k]);
    benchmark::DoNotOptimize(c);
    iters += c.iterations;
    ++n;
  });
  state.counters["iterations"] = double(iters) / double(n);
}
BENCHMARK(BM_WarmContact);

// a contact of the previous step (no Wang test: the warm iteration decides)
void BM_PipelineContinuingContact(benchmark::State &state)
{
  const PipelineCounters cnt = time_pipeline(state, overlapping());
  state.counters["continued_fraction"] = double(cnt.continued) / double(cnt.pairs);
}
BENCHMARK(BM_PipelineContinuingContact);

void BM_ColdContact(benchmark::State &state)
{
  const auto &pairs = overlapping();
  ContactSettings st;
  long long iters = 0, n = 0;
  cycle(state, [&](int k) {
    auto c = ellipsoid_contact(pairs[k].a, pairs[k].b, st);
    benchmark::DoNotOptimize(c);
    iters += c.iterations;
    ++n;
  });
  state.counters["iterations"] = double(iters) / double(n);
}
BENCHMARK(BM_ColdContact);

// paper's fast mode: Perram-type vector accepted when within 0.1 rad of the gradients
void BM_ColdContactFastMode(benchmark::State &state)
{
  const auto &pairs = overlapping();
  ContactSettings st;
  st.correction_angle = 0.1;
  cycle(state, [&](int k) {
    auto c = ellipsoid_contact(pairs[k].a, pairs[k].b, st);
    benchmark::DoNotOptimize(c);
  });
}
BENCHMARK(BM_ColdContactFastMode);

void BM_SpherePath(benchmark::State &state)
{
  static const auto pairs = make_pairs(1e-3, true, 3);
  ContactSettings st;
  cycle(state, [&](int k) {
    auto c = ellipsoid_contact(pairs[k].a, pairs[k].b, st);
    benchmark::DoNotOptimize(c);
  });
}
BENCHMARK(BM_SpherePath);

}    // namespace

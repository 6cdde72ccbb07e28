#include "physics/impact/impact_table.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>

namespace snooker::physics {
namespace {

constexpr double kHalfPi = std::numbers::pi / 2;
// A rolling ball's cloth slip is zero up to rounding; anything above this (relative
// to V) is a sliding ball, which the tables do not cover.
constexpr double kRollingSlip = 1e-9;
constexpr double kKeyMatch = 1e-12;
constexpr char kMagic[8] = {'S', 'N', 'K', 'G', 'R', 'I', 'D', '1'};
constexpr std::uint32_t kFailed = 0xffffffffu;
constexpr double kCushionKind = 1, kBallBallKind = 2;  // key[0] of each kind of table
constexpr int kCushionOutputs = 5;    // v_x, v_y, R w after, over V
constexpr int kBallBallOutputs = 12;  // v, R w of C and of O after, over V

bool Near(double a, double b) { return std::abs(a - b) <= kKeyMatch * std::max(1.0, std::abs(b)); }

// Lagrange weights of one axis: the 4 nodes first..first+3 (2 on an axis of 2-3
// nodes, 1 on an axis of one), the same stencil for every point of a cell.
struct Stencil {
  int first = 0;
  int count = 1;
  std::array<double, 4> w{1, 0, 0, 0};
};

int StencilCount(int nodes) { return nodes <= 1 ? 1 : (nodes < 4 ? 2 : 4); }
int StencilFirst(int cell, int nodes) {
  if (nodes <= 1) return 0;
  return nodes < 4 ? cell : std::clamp(cell - 1, 0, nodes - 4);
}
int Cells(int nodes) { return nodes > 1 ? nodes - 1 : 1; }
int CellOf(double g, int nodes) {
  return nodes > 1 ? std::clamp(static_cast<int>(g), 0, nodes - 2) : 0;
}

Stencil AxisStencil(double g, int nodes) {
  Stencil st;
  if (nodes <= 1) return st;
  const int cell = CellOf(g, nodes);
  st.first = StencilFirst(cell, nodes);
  st.count = StencilCount(nodes);
  const double u = g - st.first;
  if (st.count == 2) {
    st.w = {1 - u, u, 0, 0};
  } else {
    st.w = {-(u - 1) * (u - 2) * (u - 3) / 6, u * (u - 2) * (u - 3) / 2,
            -u * (u - 1) * (u - 3) / 2, u * (u - 1) * (u - 2) / 6};
  }
  return st;
}

// Grid coordinate (fractional node index) of x on an axis; NaN outside it.
double GridCoordinate(double x, const TableAxis& a) {
  if (a.nodes <= 1) return Near(x, a.lo) ? 0.0 : std::numeric_limits<double>::quiet_NaN();
  const double g = (x - a.lo) / (a.hi - a.lo) * (a.nodes - 1);
  return g >= 0 && g <= a.nodes - 1 ? g : std::numeric_limits<double>::quiet_NaN();
}

double AxisValue(const TableAxis& a, double g) {
  return a.nodes > 1 ? a.lo + (a.hi - a.lo) * g / (a.nodes - 1) : a.lo;
}

void PutBytes(std::vector<std::uint8_t>* out, const void* p, std::size_t n) {
  const std::size_t at = out->size();
  out->resize(at + n);
  std::memcpy(out->data() + at, p, n);
}
template <typename T>
void Put(std::vector<std::uint8_t>* out, const T& v) {
  PutBytes(out, &v, sizeof(T));
}
template <typename T>
bool Get(const std::uint8_t* data, std::size_t size, std::size_t* at, T* v) {
  if (size - *at < sizeof(T)) return false;
  std::memcpy(v, data + *at, sizeof(T));
  *at += sizeof(T);
  return true;
}

// Nodes of a grid, and the index of node (i0, i1, i2) (axis 0 fastest).
std::size_t NodeCount(const std::array<TableAxis, 3>& axes) {
  return static_cast<std::size_t>(axes[0].nodes) * static_cast<std::size_t>(axes[1].nodes) *
         static_cast<std::size_t>(axes[2].nodes);
}
std::size_t NodeIndex(const std::array<TableAxis, 3>& axes, int i0, int i1, int i2) {
  return (static_cast<std::size_t>(i2) * static_cast<std::size_t>(axes[1].nodes) +
          static_cast<std::size_t>(i1)) * static_cast<std::size_t>(axes[0].nodes) +
         static_cast<std::size_t>(i0);
}

// The reflection X -> -X of a ball's state: v_x, w_y and w_z change sign.
BallMotion Mirror(const BallMotion& m) {
  return {Vec3(-m.v.x(), m.v.y(), m.v.z()), Vec3(m.w.x(), -m.w.y(), -m.w.z())};
}

bool Rolling(const BallMotion& m, double radius, double speed) {
  const double slip = std::abs(m.v.x() - radius * m.w.y()) + std::abs(m.v.y() + radius * m.w.x());
  return slip <= kRollingSlip * speed;  // false for NaN
}

}  // namespace

namespace {

// GridTable::Deserialize, and then a check that the table is of the expected kind;
// `out` is untouched on error.
std::string DeserializeKind(const std::uint8_t* data, std::size_t size, bool borrow, double kind,
                            int outputs, const char* name, GridTable* out) {
  GridTable g;
  std::string error = GridTable::Deserialize(data, size, borrow, &g);
  if (!error.empty()) return error;
  if (g.key()[0] != kind || g.outputs() != outputs) return std::string("not a ") + name + " table";
  *out = std::move(g);
  return {};
}

}  // namespace

std::uint32_t TransitionSignature(std::initializer_list<ContactTransitions> contacts) {
  std::uint32_t s = 0;
  int shift = 0;
  auto sat = [](int n) { return static_cast<std::uint32_t>(std::min(n, 15)); };
  for (const ContactTransitions& c : contacts) {
    if (shift > 20) break;
    s |= (sat(c.stick) | sat(c.unstick) << 4 | sat(c.reverse) << 8) << shift;
    shift += 12;
  }
  return s;
}

// ---- GridTable --------------------------------------------------------------------

std::size_t GridTable::Node(const std::array<int, kDims>& i) const {
  return NodeIndex(axes_, i[0], i[1], i[2]);
}
std::size_t GridTable::Cell(const std::array<int, kDims>& i) const {
  return (static_cast<std::size_t>(i[2]) * static_cast<std::size_t>(Cells(axes_[1].nodes)) +
          static_cast<std::size_t>(i[1])) * static_cast<std::size_t>(Cells(axes_[0].nodes)) +
         static_cast<std::size_t>(i[0]);
}
int GridTable::cells() const {
  return Cells(axes_[0].nodes) * Cells(axes_[1].nodes) * Cells(axes_[2].nodes);
}
int GridTable::marked_cells() const {
  return static_cast<int>(std::count(marked_.begin(), marked_.end(), std::uint8_t{1}));
}

GridTable GridTable::Build(const Key& key, const std::array<TableAxis, kDims>& axes, int outputs,
                           double cell_tolerance, const Sampler& sample) {
  GridTable t;
  t.key_ = key;
  t.axes_ = axes;
  t.outputs_ = std::clamp(outputs, 1, kMaxOutputs);
  t.cell_tolerance_ = cell_tolerance;
  const std::size_t nodes = NodeCount(axes);
  const std::size_t k_out = static_cast<std::size_t>(t.outputs_);
  t.owned_.assign(nodes * k_out, 0.0);
  t.values_ = t.owned_.data();
  std::vector<std::uint32_t> signature(nodes, kFailed);
  std::array<int, kDims> i{};
  for (i[2] = 0; i[2] < axes[2].nodes; ++i[2]) {
    for (i[1] = 0; i[1] < axes[1].nodes; ++i[1]) {
      for (i[0] = 0; i[0] < axes[0].nodes; ++i[0]) {
        const std::size_t n = t.Node(i);
        std::uint32_t sig = 0;
        const std::array<double, kDims> x{AxisValue(axes[0], i[0]), AxisValue(axes[1], i[1]),
                                          AxisValue(axes[2], i[2])};
        if (sample(x, t.owned_.data() + n * k_out, &sig)) signature[n] = sig;
      }
    }
  }
  t.marked_.assign(static_cast<std::size_t>(t.cells()), 0);
  std::array<int, kDims> c{};
  std::array<double, kMaxOutputs> exact{}, approx{};
  for (c[2] = 0; c[2] < Cells(axes[2].nodes); ++c[2]) {
    for (c[1] = 0; c[1] < Cells(axes[1].nodes); ++c[1]) {
      for (c[0] = 0; c[0] < Cells(axes[0].nodes); ++c[0]) {
        std::array<int, kDims> first{}, count{};
        for (int d = 0; d < kDims; ++d) {
          first[d] = StencilFirst(c[d], axes[d].nodes);
          count[d] = StencilCount(axes[d].nodes);
        }
        // One transition signature across the stencil, every solve successful.
        const std::uint32_t sig0 = signature[t.Node(first)];
        bool ok = sig0 != kFailed;
        std::array<int, kDims> j{};
        for (j[2] = first[2]; ok && j[2] < first[2] + count[2]; ++j[2]) {
          for (j[1] = first[1]; ok && j[1] < first[1] + count[1]; ++j[1]) {
            for (j[0] = first[0]; ok && j[0] < first[0] + count[0]; ++j[0]) {
              ok = signature[t.Node(j)] == sig0;
            }
          }
        }
        if (ok) {  // the interpolant against the exact map at the cell's centre
          std::array<double, kDims> g{}, x{};
          for (int d = 0; d < kDims; ++d) {
            g[d] = axes[d].nodes > 1 ? c[d] + 0.5 : 0.0;
            x[d] = AxisValue(axes[d], g[d]);
          }
          std::uint32_t sig = 0;
          ok = sample(x, exact.data(), &sig);
          t.Interpolate(g, approx.data());
          for (int k = 0; ok && k < t.outputs_; ++k) {
            ok = std::abs(approx[static_cast<std::size_t>(k)] - exact[static_cast<std::size_t>(k)]) <=
                 cell_tolerance;
          }
        }
        t.marked_[t.Cell(c)] = ok ? 0 : 1;
      }
    }
  }
  return t;
}

namespace {

// The tensor sum over the stencils of `outputs` values a node. K > 0 fixes the count
// at compile time (the compiler unrolls the inner loop: lookups are on the
// simulator's hot path); K = 0 takes it at run time.
template <int K>
void SumStencils(const double* values, const std::array<TableAxis, 3>& axes, const Stencil& s0,
                 const Stencil& s1, const Stencil& s2, int outputs, double* out) {
  const int k_out = K > 0 ? K : outputs;
  std::array<double, GridTable::kMaxOutputs> acc{};
  for (int d2 = 0; d2 < s2.count; ++d2) {
    for (int d1 = 0; d1 < s1.count; ++d1) {
      const double w12 = s2.w[static_cast<std::size_t>(d2)] * s1.w[static_cast<std::size_t>(d1)];
      const double* row = values + NodeIndex(axes, s0.first, s1.first + d1, s2.first + d2) *
                                       static_cast<std::size_t>(k_out);
      for (int d0 = 0; d0 < s0.count; ++d0) {
        const double w = w12 * s0.w[static_cast<std::size_t>(d0)];
        for (int k = 0; k < k_out; ++k) acc[static_cast<std::size_t>(k)] += w * row[d0 * k_out + k];
      }
    }
  }
  std::copy(acc.begin(), acc.begin() + k_out, out);
}

}  // namespace

void GridTable::Interpolate(const std::array<double, kDims>& g, double* outputs) const {
  const Stencil s0 = AxisStencil(g[0], axes_[0].nodes);
  const Stencil s1 = AxisStencil(g[1], axes_[1].nodes);
  const Stencil s2 = AxisStencil(g[2], axes_[2].nodes);
  switch (outputs_) {  // the two tables' counts, unrolled
    case kCushionOutputs:
      SumStencils<kCushionOutputs>(values_, axes_, s0, s1, s2, outputs_, outputs);
      return;
    case kBallBallOutputs:
      SumStencils<kBallBallOutputs>(values_, axes_, s0, s1, s2, outputs_, outputs);
      return;
    default: SumStencils<0>(values_, axes_, s0, s1, s2, outputs_, outputs);
  }
}

bool GridTable::Lookup(const std::array<double, kDims>& x, double* outputs) const {
  if (values_ == nullptr) return false;
  std::array<double, kDims> g{};
  std::array<int, kDims> c{};
  for (int d = 0; d < kDims; ++d) {
    g[d] = GridCoordinate(x[d], axes_[d]);
    if (std::isnan(g[d])) return false;
    c[d] = CellOf(g[d], axes_[d].nodes);
  }
  if (marked_[Cell(c)] != 0) return false;
  Interpolate(g, outputs);
  return true;
}

std::vector<std::uint8_t> GridTable::Serialize() const {
  std::vector<std::uint8_t> out;
  PutBytes(&out, kMagic, sizeof(kMagic));
  for (double k : key_) Put(&out, k);
  for (const TableAxis& a : axes_) {
    Put(&out, a.lo);
    Put(&out, a.hi);
    Put(&out, static_cast<std::int64_t>(a.nodes));
  }
  Put(&out, static_cast<std::int64_t>(outputs_));
  Put(&out, cell_tolerance_);
  const std::uint64_t nv = NodeCount(axes_) * static_cast<std::size_t>(outputs_);
  Put(&out, nv);
  Put(&out, static_cast<std::uint64_t>(marked_.size()));
  PutBytes(&out, values_, nv * sizeof(double));
  PutBytes(&out, marked_.data(), marked_.size());
  return out;
}

std::string GridTable::Deserialize(const std::uint8_t* data, std::size_t size, bool borrow,
                                   GridTable* out) {
  if (data == nullptr || size < sizeof(kMagic) || std::memcmp(data, kMagic, sizeof(kMagic)) != 0) {
    return "not an impact table (bad magic, or " + std::to_string(size) + " bytes)";
  }
  GridTable t;
  std::size_t at = sizeof(kMagic);
  bool ok = true;
  for (double& k : t.key_) ok = ok && Get(data, size, &at, &k);
  for (TableAxis& a : t.axes_) {
    std::int64_t nodes = 0;
    ok = ok && Get(data, size, &at, &a.lo) && Get(data, size, &at, &a.hi) &&
         Get(data, size, &at, &nodes);
    a.nodes = nodes >= 1 && nodes <= 100000 ? static_cast<int>(nodes) : 0;
  }
  std::int64_t outputs = 0;
  std::uint64_t nv = 0, nm = 0;
  ok = ok && Get(data, size, &at, &outputs) && Get(data, size, &at, &t.cell_tolerance_) &&
       Get(data, size, &at, &nv) && Get(data, size, &at, &nm);
  if (!ok) return "impact table truncated in its header";
  for (const TableAxis& a : t.axes_) {
    if (a.nodes < 1 || !std::isfinite(a.lo) || !std::isfinite(a.hi) ||
        (a.nodes > 1 && !(a.hi > a.lo))) {
      return "impact table has an invalid axis";
    }
  }
  if (outputs < 1 || outputs > kMaxOutputs) return "impact table has an invalid output count";
  t.outputs_ = static_cast<int>(outputs);
  const std::uint64_t nodes = NodeCount(t.axes_);  // each axis at most 1e5 nodes: no overflow
  if (nv != nodes * static_cast<std::uint64_t>(outputs) ||
      nm != static_cast<std::uint64_t>(t.cells())) {
    return "impact table sizes do not match its grid";
  }
  if (size - at != nv * sizeof(double) + nm) return "impact table has the wrong length";
  const std::uint8_t* values = data + at;
  if (borrow && reinterpret_cast<std::uintptr_t>(values) % alignof(double) == 0) {
    t.values_ = reinterpret_cast<const double*>(values);
  } else {
    t.owned_.resize(nv);
    std::memcpy(t.owned_.data(), values, nv * sizeof(double));
    t.values_ = t.owned_.data();
  }
  for (std::uint64_t i = 0; i < nv; ++i) {
    if (!std::isfinite(t.values_[i])) return "impact table holds a non-finite value";
  }
  t.marked_.assign(values + nv * sizeof(double), values + nv * sizeof(double) + nm);
  *out = std::move(t);
  if (!out->owned_.empty()) out->values_ = out->owned_.data();
  return {};
}

// ---- CushionTable -----------------------------------------------------------------

namespace {

GridTable::Key CushionKey(const BallParams& ball, const CushionParams& cushion) {
  double e_lo = cushion.e_e, e_hi = cushion.e_e;
  const RestitutionCurve& c = cushion.restitution_curve;
  for (int i = 0; i < c.points && i < RestitutionCurve::kMaxPoints; ++i) {
    const double e = c.e[static_cast<std::size_t>(i)];
    e_lo = i == 0 ? e : std::min(e_lo, e);
    e_hi = i == 0 ? e : std::max(e_hi, e);
  }
  return {kCushionKind, ball.mass * ball.radius * ball.radius / ball.Inertia(),
          CushionSinTheta(ball, cushion), cushion.mu_w, cushion.mu_s, e_lo, e_hi, 0.0};
}

}  // namespace

CushionTable CushionTable::Build(const BallParams& ball, const CushionParams& cushion,
                                 const CushionTableGrid& grid) {
  const GridTable::Key key = CushionKey(ball, cushion);
  const double e_lo = key[5], e_hi = key[6];
  const std::array<TableAxis, 3> axes{TableAxis{grid.min_angle, kHalfPi, grid.angles},
                                      TableAxis{-grid.max_side, grid.max_side, grid.sides},
                                      TableAxis{e_lo, e_hi, e_hi > e_lo ? grid.restitutions : 1}};
  ImpulseSolverOptions o;
  o.tolerance = grid.build_tolerance;
  o.method = ImpulseMethod::kDormandPrince853;
  const double R = ball.radius;
  auto sample = [&](const std::array<double, 3>& x, double* g, std::uint32_t* sig) {
    CushionParams p = cushion;
    p.restitution_curve = {};
    p.e_e = x[2];
    const CushionImpactResult r =
        ResolveCushionImpact(CushionIncidentState(1.0, x[0], 1.0 / R, x[1] / R), ball, p, o);
    if (r.status != ImpactStatus::kOk) return false;
    const double out[kCushionOutputs] = {r.out.v.x(), r.out.v.y(), R * r.out.w.x(), R * r.out.w.y(),
                           R * r.out.w.z()};
    std::copy(out, out + kCushionOutputs, g);
    *sig = TransitionSignature({r.cushion, r.cloth});
    return true;
  };
  CushionTable t;
  t.table_ = GridTable::Build(key, axes, kCushionOutputs, grid.cell_tolerance, sample);
  return t;
}

std::string CushionTable::Deserialize(const std::uint8_t* data, std::size_t size, bool borrow,
                                      CushionTable* out) {
  return DeserializeKind(data, size, borrow, kCushionKind, kCushionOutputs, "cushion", &out->table_);
}

bool CushionTable::Matches(const BallParams& ball, const CushionParams& cushion) const {
  if (table_.empty()) return false;
  const GridTable::Key k = CushionKey(ball, cushion), &t = table_.key();
  for (int i = 0; i < 5; ++i) {
    if (!Near(k[static_cast<std::size_t>(i)], t[static_cast<std::size_t>(i)])) return false;
  }
  return k[5] >= t[5] - kKeyMatch && k[6] <= t[6] + kKeyMatch;
}

bool CushionTable::Lookup(const BallMotion& in, double radius, double e, BallMotion* out) const {
  const double vx = in.v.x(), vy = in.v.y(), R = radius;
  if (!(vy > 0)) return false;
  const double V = std::sqrt(vx * vx + vy * vy);
  if (!Rolling(in, R, V)) return false;
  const bool mirror = vx < 0;
  const std::array<double, 3> x{std::atan2(vy, std::abs(vx)), (mirror ? -R : R) * in.w.z() / V, e};
  double g[kCushionOutputs];
  if (!table_.Lookup(x, g)) return false;
  const BallMotion m{Vec3(V * g[0], V * g[1], 0.0), Vec3(g[2], g[3], g[4]) * (V / R)};
  *out = mirror ? Mirror(m) : m;
  return true;
}

// ---- BallBallTable ----------------------------------------------------------------

namespace {

GridTable::Key BallBallKey(const BallParams& ball, const BallBallParams& contact, double mu_s) {
  return {kBallBallKind, ball.mass * ball.radius * ball.radius / ball.Inertia(), contact.mu_bb,
          contact.e, mu_s, 0.0, 0.0, 0.0};
}

}  // namespace

BallBallTable BallBallTable::Build(const BallParams& ball, const BallBallParams& contact,
                                   double mu_s, const BallBallTableGrid& grid) {
  const std::array<TableAxis, 3> axes{TableAxis{0.0, grid.max_cut, grid.cuts},
                                      TableAxis{-grid.max_side, grid.max_side, grid.sides},
                                      TableAxis{0.0, 0.0, 1}};
  ImpulseSolverOptions o;
  o.tolerance = grid.build_tolerance;
  o.method = ImpulseMethod::kDormandPrince853;
  const double R = ball.radius;
  BallBallParams constant = contact;
  constant.friction_law = BallBallFrictionLaw::kConstant;
  auto sample = [&](const std::array<double, 3>& x, double* g, std::uint32_t* sig) {
    const ImpactResult r =
        ResolveImpact(PaperIncidentState(1.0, 1.0 / R, x[1] / R, x[0]), ball, constant, mu_s, o);
    if (r.status != ImpactStatus::kOk) return false;
    const ImpactState& s = r.out;
    const double out[kBallBallOutputs] = {s.c.v.x(),     s.c.v.y(),     s.c.v.z(),     R * s.c.w.x(),
                            R * s.c.w.y(), R * s.c.w.z(), s.o.v.x(),     s.o.v.y(),
                            s.o.v.z(),     R * s.o.w.x(), R * s.o.w.y(), R * s.o.w.z()};
    std::copy(out, out + kBallBallOutputs, g);
    *sig = TransitionSignature({r.a, r.d, r.b}) ^
           (static_cast<std::uint32_t>(std::min<int>(r.c_liftoffs, 3)) << 28) ^
           (static_cast<std::uint32_t>(std::min<int>(r.o_liftoffs, 3)) << 30);
    return true;
  };
  BallBallTable t;
  t.table_ = GridTable::Build(BallBallKey(ball, contact, mu_s), axes, kBallBallOutputs,
                              grid.cell_tolerance, sample);
  return t;
}

std::string BallBallTable::Deserialize(const std::uint8_t* data, std::size_t size, bool borrow,
                                       BallBallTable* out) {
  return DeserializeKind(data, size, borrow, kBallBallKind, kBallBallOutputs, "ball-ball",
                         &out->table_);
}

bool BallBallTable::Matches(const BallParams& ball, const BallBallParams& contact,
                            double mu_s) const {
  if (table_.empty() || contact.friction_law != BallBallFrictionLaw::kConstant) return false;
  const GridTable::Key k = BallBallKey(ball, contact, mu_s), &t = table_.key();
  for (std::size_t i = 0; i < k.size(); ++i) {
    if (!Near(k[i], t[i])) return false;
  }
  return true;
}

bool BallBallTable::Lookup(const ImpactState& in, double radius, ImpactState* out) const {
  const BallMotion& c = in.c;
  if (!in.o.v.isZero(0.0) || !in.o.w.isZero(0.0) || c.v.z() != 0.0) return false;
  const double vx = c.v.x(), vy = c.v.y(), R = radius;
  if (!(vy > 0)) return false;
  const double V = std::sqrt(vx * vx + vy * vy);
  if (!Rolling(c, R, V)) return false;
  const bool mirror = vx < 0;
  const std::array<double, 3> x{std::atan2(std::abs(vx), vy), (mirror ? -R : R) * c.w.z() / V, 0.0};
  double g[kBallBallOutputs];
  if (!table_.Lookup(x, g)) return false;
  const double w = V / R;
  ImpactState s;
  s.c = {Vec3(g[0], g[1], g[2]) * V, Vec3(g[3], g[4], g[5]) * w};
  s.o = {Vec3(g[6], g[7], g[8]) * V, Vec3(g[9], g[10], g[11]) * w};
  *out = mirror ? ImpactState{Mirror(s.c), Mirror(s.o)} : s;
  return true;
}

}  // namespace snooker::physics

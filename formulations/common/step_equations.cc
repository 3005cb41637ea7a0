#include "formulations/common/step_equations.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace cb {

struct StepEquationSystem::PatternCache {
  const ContactModel* model = nullptr;
  ConstraintKind kind = ConstraintKind::kArcLength;
  int index = -1;
  bool has_rho = false;
  long nnz_curvature = -1;
  long nnz_gap = -1;
  std::vector<int> load_rows;  // rows where f != 0
  ScatterPattern pattern;
  std::size_t first_stiffness = 0, first_curvature = 0, first_gap_t = 0, first_rest = 0;
  std::size_t first_gap = 0;
};

std::shared_ptr<StepEquationSystem::PatternCache> StepEquationSystem::MakePatternCache() {
  return std::make_shared<PatternCache>();
}

StepEquationSystem::StepEquationSystem(const StepProblem& step, bool has_rho,
                                       std::shared_ptr<PatternCache> cache)
    : step_(step),
      layout_{step.num_dofs(), step.num_pairs(), has_rho},
      cache_(cache ? std::move(cache) : std::make_shared<PatternCache>()),
      structure_{step.num_dofs(), step.num_pairs(), step.scales.length},
      has_structure_(step.model->has_energy()) {}

StepEquationSystem::~StepEquationSystem() = default;

StepEquationSystem::Unknowns StepEquationSystem::Split(const Vec& x) {
  const StepEquationLayout& l = layout_;
  Unknowns unknowns{x.segment(l.du(), l.d), x.segment(l.g(), l.nc), x.segment(l.r(), l.nc),
                    x[l.dlambda()], l.has_rho ? x[l.rho()] : 0.0};
  u_ = step_.base.u + unknowns.du;
  return unknowns;
}

bool StepEquationSystem::Residual(const Vec& x, Vec* residual) {
  const Unknowns unknowns = Split(x);
  step_.model->InternalForce(u_, &internal_);
  // grad phi^T r^, without assembling grad phi.
  step_.model->GapsAndReaction(u_, unknowns.r, &phi_, &reaction_);
  return FillResidual(x, unknowns, residual);
}

void StepEquationSystem::Jacobian(const Vec& x, SpMat* jacobian) {
  const Unknowns unknowns = Split(x);
  reaction_force_ = step_.scales.force * unknowns.r;
  step_.model->GapDerivatives(u_, reaction_force_, &gap_jacobian_, &curvature_);
  StartJacobian(jacobian);
  const std::vector<int>& slots = cache_->pattern.slots();
  step_.model->AddStiffness(u_, 1.0 / step_.scales.force, slots.data() + cache_->first_stiffness,
                            jacobian->valuePtr());
  FillJacobian(x, unknowns, jacobian);
}

// Each member's kinematics and each pair's obstacle evaluated once for both; the values are
// those of Residual and Jacobian to the last bit.
bool StepEquationSystem::ResidualAndJacobian(const Vec& x, Vec* residual, SpMat* jacobian) {
  const Unknowns unknowns = Split(x);
  const ContactModel& model = *step_.model;
  reaction_force_ = step_.scales.force * unknowns.r;
  model.GapsReactionAndDerivatives(u_, unknowns.r, reaction_force_, &phi_, &reaction_,
                                   &gap_jacobian_, &curvature_);
  StartJacobian(jacobian);
  const std::vector<int>& slots = cache_->pattern.slots();
  model.InternalForceAndStiffness(u_, &internal_, 1.0 / step_.scales.force,
                                  slots.data() + cache_->first_stiffness, jacobian->valuePtr());
  FillJacobian(x, unknowns, jacobian);
  return FillResidual(x, unknowns, residual);
}

bool StepEquationSystem::ResidualFloor(const Vec& x, Vec* floor) {
  // A sum of n rounded terms is typically within sqrt(n) eps of their magnitudes' sum; a row of
  // (29) has at most a few dozen.
  constexpr double kRoundingUnits = 8.0;
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  Vec f;
  if (!Residual(x, &f)) return false;  // sets u_ and reaction_
  const ContactModel& model = *step_.model;
  model.InternalForceMagnitudes(u_, &force_magnitudes_);
  const double lambda = step_.base.lambda + x[layout_.dlambda()];
  floor->setZero(layout_.size());
  floor->head(layout_.d) =
      kRoundingUnits * kEps *
      ((force_magnitudes_ + std::abs(lambda) * model.load_pattern().cwiseAbs()) /
           step_.scales.force +
       reaction_.cwiseAbs());
  return floor->allFinite();
}

// The rows from internal_, phi_ and reaction_ at u_.
bool StepEquationSystem::FillResidual(const Vec& x, const Unknowns& unknowns, Vec* residual) const {
  const ContactModel& model = *step_.model;
  const StepEquationLayout& l = layout_;
  const double length = step_.scales.length;
  const double force = step_.scales.force;
  const auto& [du, g, r, dlambda, rho] = unknowns;
  residual->resize(l.size());
  const double lambda = step_.base.lambda + dlambda;
  residual->segment(0, l.d) =
      (internal_ - lambda * model.load_pattern()) / force - reaction_;  // (29) / R
  residual->segment(l.d, l.nc) = g + phi_ / length;                     // (30) / L
  const int row3 = l.complementarity_row();
  for (int p = 0; p < l.nc; ++p) (*residual)[row3 + p] = Complementarity(g[p], -r[p], rho);
  if (step_.constraint.kind == ConstraintKind::kKink) {
    // With (53), g^ = r^, every complementarity function used here is a cone in g^ on that
    // line (sqrt(2 (g^2 + rho^2)) for psi, -|g^| for min) whose apex is the kink, where Newton
    // stagnates. On (53) C = 0 is equivalent to g^ = r^ = 0, stated smoothly here as
    // g^ + r^ = 0; the solution set is unchanged and the Jacobian stays regular.
    const int p = step_.constraint.index;
    (*residual)[row3 + p] = g[p] + r[p];
  }
  if (l.has_rho) (*residual)[l.extra_row()] = ExtraRow(x);
  (*residual)[l.constraint_row()] =
      StepConstraintValue(step_, du, dlambda, length * g, force * r);  // (33) etc.
  return residual->allFinite();
}

bool StepEquationSystem::CacheHoldsThisSystem() const {
  const PatternCache& cache = *cache_;
  const StepConstraint& c = step_.constraint;
  return cache.model == step_.model && cache.kind == c.kind && cache.index == c.index &&
         cache.has_rho == layout_.has_rho && cache.nnz_curvature >= 0;
}

const SpMat& StepEquationSystem::JacobianPattern(const Vec& x) {
  if (!CacheHoldsThisSystem()) {
    // The blocks' patterns depend on neither u nor r (ContactModel::GapCurvature), so those
    // at x serve; the stiffness enters through its entries alone.
    const auto unknowns = Split(x);
    reaction_force_ = step_.scales.force * unknowns.r;
    step_.model->GapDerivatives(u_, reaction_force_, &gap_jacobian_, &curvature_);
    BuildPattern();
  }
  return cache_->pattern.pattern();
}

void StepEquationSystem::BuildPattern() {
  const ContactModel& model = *step_.model;
  const StepEquationLayout& l = layout_;
  const int row3 = l.complementarity_row();
  const int row5 = l.constraint_row();
  const StepConstraint& c = step_.constraint;
  PatternCache& cache = *cache_;
  // Entries in the order the fill below adds them.
  std::vector<ScatterPattern::Entry> e;
  const std::vector<std::pair<int, int>> stiffness_entries = model.StiffnessEntries();
  // Room for every entry at once (the extra row: at most 2 nc + 1), on huge pages: grown by
  // doubling it was copied ~log2(nnz) times into fresh pages.
  const std::size_t bound = stiffness_entries.size() + curvature_.nonZeros() +
                            2 * static_cast<std::size_t>(gap_jacobian_.nonZeros()) +
                            2 * static_cast<std::size_t>(l.d) + 6 * static_cast<std::size_t>(l.nc) +
                            4;
  e.reserve(bound);
  cache.first_stiffness = e.size();
  e.insert(e.end(), stiffness_entries.begin(), stiffness_entries.end());
  cache.first_curvature = e.size();
  AppendBlockEntries(curvature_, 0, 0, false, &e);
  cache.first_gap_t = e.size();
  AppendBlockEntries(gap_jacobian_, 0, l.r(), true, &e);
  cache.first_gap = e.size();
  AppendBlockEntries(gap_jacobian_, l.d, 0, false, &e);
  cache.first_rest = e.size();
  cache.load_rows.clear();
  const Vec& f = model.load_pattern();
  for (int i = 0; i < l.d; ++i) {
    if (f[i] != 0.0) cache.load_rows.push_back(i);
  }
  for (int i : cache.load_rows) e.emplace_back(i, l.dlambda());
  for (int p = 0; p < l.nc; ++p) e.emplace_back(l.d + p, l.g() + p);
  for (int p = 0; p < l.nc; ++p) {
    e.emplace_back(row3 + p, l.g() + p);
    e.emplace_back(row3 + p, l.r() + p);
    if (l.has_rho) e.emplace_back(row3 + p, l.rho());
  }
  if (l.has_rho) AppendExtraRowEntries(&e);
  switch (c.kind) {
    case ConstraintKind::kArcLength:
      for (int j = 0; j < l.d; ++j) e.emplace_back(row5, j);
      e.emplace_back(row5, l.dlambda());
      break;
    case ConstraintKind::kFixedLoad:
      e.emplace_back(row5, l.dlambda());
      break;
    case ConstraintKind::kDisplacement:
      e.emplace_back(row5, c.index);
      break;
    case ConstraintKind::kKink:
      e.emplace_back(row5, l.g() + c.index);
      e.emplace_back(row5, l.r() + c.index);
      break;
    case ConstraintKind::kHyperplane:  // dense, as the normal's zeros may move between steps
      for (int j = 0; j < l.d; ++j) e.emplace_back(row5, j);
      e.emplace_back(row5, l.dlambda());
      break;
  }
  cache.pattern = ScatterPattern(l.size(), l.size(), e);
  cache.model = &model;
  cache.kind = c.kind;
  cache.index = c.index;
  cache.has_rho = l.has_rho;
  cache.nnz_curvature = curvature_.nonZeros();
  cache.nnz_gap = gap_jacobian_.nonZeros();
}

// The pattern (built when the cache does not fit this system or the gap blocks' sizes changed)
// and the Jacobian's values zeroed on it; gap_jacobian_ and curvature_ are current.
void StepEquationSystem::StartJacobian(SpMat* jacobian) {
  PatternCache& cache = *cache_;
  if (!CacheHoldsThisSystem() || cache.nnz_curvature != curvature_.nonZeros() ||
      cache.nnz_gap != gap_jacobian_.nonZeros()) {
    BuildPattern();
  }
  cache.pattern.Reset(jacobian);
}

// Every block but the stiffness, which the caller added after StartJacobian.
void StepEquationSystem::FillJacobian(const Vec& x, const Unknowns& unknowns,
                                      SpMat* jacobian) const {
  const ContactModel& model = *step_.model;
  const StepEquationLayout& l = layout_;
  const double length = step_.scales.length;
  const double force = step_.scales.force;
  const auto& [du, g, r, dlambda, rho] = unknowns;
  const StepConstraint& c = step_.constraint;
  const PatternCache& cache = *cache_;
  const std::vector<int>& slots = cache.pattern.slots();
  // dF1/ddu = (hess pi - sum_p r_p hess phi_p) / R, dF1/dr^ = -grad phi^T.
  ScatterBlock(curvature_, -1.0 / force, slots, cache.first_curvature, jacobian);
  ScatterBlock(gap_jacobian_, -1.0, slots, cache.first_gap_t, jacobian);
  // dF2/ddu = grad phi / L.
  ScatterBlock(gap_jacobian_, 1.0 / length, slots, cache.first_gap, jacobian);
  Cursor cursor{jacobian->valuePtr(), slots.data(), cache.first_rest};
  const Vec& f = model.load_pattern();
  for (int i : cache.load_rows) cursor.Add(-f[i] / force);  // dF1/ddlambda
  for (int p = 0; p < l.nc; ++p) cursor.Add(1.0);           // dF2/dg^
  const int kink_pair = c.kind == ConstraintKind::kKink ? c.index : -1;
  for (int p = 0; p < l.nc; ++p) {
    if (p == kink_pair) {  // the row g^ + r^ of the kink pair (see FillResidual)
      cursor.Add(1.0);
      cursor.Add(1.0);
      if (l.has_rho) cursor.Skip();
      continue;
    }
    // C(a, b, rho) with a = g^, b = -r^.
    double d_a = 0.0, d_b = 0.0, d_rho = 0.0;
    ComplementarityElement(g[p], -r[p], rho, &d_a, &d_b, &d_rho);
    cursor.Add(d_a);   // dF3/dg^
    cursor.Add(-d_b);  // dF3/dr^ (b = -r^)
    if (l.has_rho) cursor.Add(d_rho);
  }
  if (l.has_rho) FillExtraRow(x, &cursor);
  switch (c.kind) {
    case ConstraintKind::kArcLength: {
      const double t2 = c.arc_length * c.arc_length;
      for (int j = 0; j < l.d; ++j) cursor.Add(2.0 * du[j] / t2);
      cursor.Add(2.0 * c.lambda_weight * c.lambda_weight * dlambda / t2);
      break;
    }
    case ConstraintKind::kFixedLoad:
      cursor.Add(1.0);
      break;
    case ConstraintKind::kDisplacement:
      cursor.Add(1.0 / length);
      break;
    case ConstraintKind::kKink:
      cursor.Add(1.0);
      cursor.Add(-1.0);
      break;
    case ConstraintKind::kHyperplane:
      for (int j = 0; j < l.d; ++j) cursor.Add(c.normal[j] / c.arc_length);
      cursor.Add(c.normal_lambda / c.arc_length);
      break;
  }
}

}  // namespace cb

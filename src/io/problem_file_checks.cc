#include "io/problem_file_checks.h"

#include <algorithm>

#include "model/rigid_motion.h"

namespace cb::io::reading {

void CheckConnected(const BodyInput& in, const std::vector<int>& uses, const char* what) {
  for (std::size_t n = 0; n < uses.size(); ++n) {
    if (uses[n] > 0) continue;
    const std::string reason =
        in.NodeName(static_cast<int>(n)) + " belongs to no " + what + " (a dangling node)";
    if (in.mesh) throw InputError(in.mesh_file, "", reason);
    in.root().Field("nodes").At(n).Fail(reason);
  }
}

void CheckHeld(const BodyInput& in, const ElasticBody& body,
               const std::vector<std::shared_ptr<const Obstacle>>& obstacles,
               const std::vector<ContactPair>& pairs) {
  const RigidMotionRestraint restraint = CheckRigidMotionRestraint(body, obstacles, pairs);
  const JsonNode where = in.root().Has("supports") ? in.root().Field("supports") : in.root();
  if (restraint.constraints == 0) {
    where.Fail(
        "no supports and no contact pairs: nothing holds the body (its stiffness is "
        "singular)");
  }
  if (restraint.free() <= 0) return;
  const std::string count =
      std::to_string(restraint.free()) + " rigid-body mode" + (restraint.free() > 1 ? "s" : "");
  const std::string& example = restraint.free_example;
  if (pairs.empty()) {
    where.Fail("the supports leave " + count + " free (e.g. " + example +
               ") and there are no contact pairs to hold the body: add supports");
  }
  where.Fail("neither the supports nor the contact pairs restrain " + count + " (e.g. " + example +
             "): the body can move freely");
}

void CheckInitialGaps(const BodyInput& in, const BodyContactModel& model,
                      const Obstacles& obstacles) {
  if (model.num_pairs() == 0) return;
  const ElasticBody& body = model.body();
  double extent = 0.0;
  for (int i = 0; i < body.num_nodes(); ++i) {
    extent = std::max(extent, body.reference(i).lpNorm<Eigen::Infinity>());
  }
  Vec phi;
  model.Gaps(Vec::Zero(model.num_dofs()), &phi);
  for (int p = 0; p < model.num_pairs(); ++p) {
    if (phi[p] > 1e-9 * std::max(extent, 1e-300)) {
      const ContactPair& pair = model.pairs()[p];
      throw InputError(in.root().file(), in.PairWhere(p),
                       in.NodeName(pair.node) + " starts inside obstacle \"" +
                           obstacles.ids[pair.obstacle] + "\" (penetration " + Describe(phi[p]) +
                           "); a half-space's normal points into the obstacle");
    }
  }
}

}  // namespace cb::io::reading

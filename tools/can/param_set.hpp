#pragma once
// Changing a node's parameters as one set: stage each change, commit them
// together (all or nothing), check that the commit applied exactly this
// host's stages and that each reads back as staged. A refusal discards
// the staged set and is rethrown as RequestError(refused) with the reason
// a person needs: the safety parameters among the changes, the whole-set
// check that failed, or the parameters that can only change at rest.
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "firmware/can/param_table.hpp"
#include "tools/can/node_client.hpp"

namespace tnv::can_host {

struct ParamAssignment {
  const fw::can::ParamDef* param = nullptr;
  double requested = 0.0;
};

// The node committed something other than what was staged (another
// host's stages, stages lost, a value changed under us).
class ParamSetMismatch : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

inline constexpr const char* kEnterCommissioning =
    "enter commissioning mode first (tnvctl commissioning enter, servo disabled)";

// "x.limits.following_floor_mm is a safety parameter: enter ..." for the
// safety parameters among `changes` (the node refused commissioning_required).
std::string safety_refusal(const std::vector<ParamAssignment>& changes);

// Why the node called the set invalid: the same whole-set check, run here
// on the node's values with the changes applied ("" when it passes).
std::string explain_invalid(NodeClient& client, const std::vector<ParamAssignment>& changes);

// Stages each change in order; returns the staged values the node read
// back. A refusal discards this host's staged set and throws.
std::vector<double> stage_params(NodeClient& client, const std::vector<ParamAssignment>& changes);

// Commits this host's staged set, `changes` being what was staged and
// `staged` the values stage_params() returned; returns the values read
// back after the commit, one per change. A refusal discards and throws
// RequestError(refused) explained; a commit that applied other than the
// staged set throws ParamSetMismatch.
std::vector<double> commit_params(NodeClient& client, const std::vector<ParamAssignment>& changes,
                                  const std::vector<double>& staged);

}  // namespace tnv::can_host

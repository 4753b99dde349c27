// A tied body for the step control's tests: it carries nothing and records what it is asked.
#pragma once

#include "dda/tied_body.h"

#include <Eigen/Dense>

#include <functional>
#include <string>
#include <vector>

namespace ddafem::dda::test_models
{
/// A tied body that carries nothing (H = 0, g = 0) and records the dt of every step begun: what
/// the far field would be factorized and condensed for. `chatters(dt)`, when set, says whether
/// its ties change state in every open-close iteration of the step of dt begun.
class RecordingBody final : public TiedBody
{
public:
  std::vector<double> dts;
  std::function<bool(double)> chatters;
  void begin_stage(StageMode) override {}
  bool stiffness_is_block_diagonal() const override { return true; }
  StepResult begin_step(double dt, const Eigen::VectorXd&) override
  {
    dts.push_back(dt);
    return {};
  }
  const Eigen::MatrixXd& stiffness() const override { return h; }
  const Eigen::VectorXd& force() const override { return g; }
  std::size_t update_trial_states(const Eigen::VectorXd&, unsigned, double, std::size_t&) override
  {
    return chatters && chatters(dts.back()) ? 1 : 0;
  }
  StepResult end_step(const Eigen::VectorXd&) override { return {}; }
  double work_on_blocks() const override { return 0.0; }

private:
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(2, 2);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(2);
};
} // namespace ddafem::dda::test_models

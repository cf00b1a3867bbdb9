#pragma once
// Torque transmission through a tortuous tube (issue 38 item 3): a wire laid through a 1.5 mm radius tube
// with three 90-degree bends (radius 10 mm, in three different planes), its proximal end turned slowly
// through a full turn and back; the tip's roll is recorded against the proximal roll.
// Inputs: wire parameters (friction, friction_torque, ... as given; the tip is made straight so that the
// roll is the wire's, not a curved tip's swing in the lumen); turn_seconds: time for one full turn
// (each way); sample_every: record every this many control steps (10 ms each).
// Output: the series and its summary; ok = false with the step's problem if the simulation failed.
#include <string>
#include <vector>

#include "base/mesh/triangle_mesh.hpp"
#include "engine/sim/step.hpp"
#include "engine/wire/wire_params.hpp"

namespace gw {

struct TorqueTransmission {
  std::vector<double> time_s, proximal_rad, tip_rad;  // proximal roll and the tip's roll about its axis
  double max_lag_rad = 0;       // largest |proximal - tip| over the run
  double final_lag_rad = 0;     // |proximal - tip| when the proximal end is back at 0 (hysteresis)
  double max_tip_rate_rad_per_s = 0;  // fastest tip roll (a whip shows as a burst well above the drive)
  double substeps_per_s = 0;    // wall-clock speed of the run [integration sub-steps / s]
  long substeps = 0;
  int split_substeps = 0;
  double mean_contacts = 0, mean_max_pgs_sweeps = 0;  // per control step
  StepTimings stages;           // summed over the turn [s]
  bool ok = true;
  std::string problem;
  TriangleMesh tube;            // the tube (for figures)
};

TorqueTransmission run_torque_transmission(const WireParams& params, double turn_seconds, int sample_every = 5);

}  // namespace gw

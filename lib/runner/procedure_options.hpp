#pragma once
// The procedure's command-line options that are not task settings, the same in navigate and evaluate: the tip
// reshape after a failed procedure (TraceOptions::reshaped, make_reshaped_task) and the per-step wall-time limit.
#include <CLI/CLI.hpp>

namespace gw {

struct ProcedureOptions {
  double reshape_tip_per_mm = 0.0;     // --reshape-tip C: 0 = never
  double reshape_tip_length_mm = 0.0;  // --reshape-tip-length L: 0 = the wire's own
  double step_time_limit_s = 0.0;      // --step-time-limit S: 0 = none
};

// Inputs: an app, the options it fills. Outputs: --reshape-tip, --reshape-tip-length, --step-time-limit declared.
void add_procedure_options(CLI::App& app, ProcedureOptions& options);

}  // namespace gw

#include "lib/runner/procedure_options.hpp"

namespace gw {

void add_procedure_options(CLI::App& app, ProcedureOptions& o) {
  CLI::Option* reshape = app.add_option("--reshape-tip", o.reshape_tip_per_mm,
                 "when a procedure does not reach the target (with --recovery: after its pull-backs), withdraw the wire, "
                 "reshape its tip to this curvature (1/mm; the wire's own is 0.2) and navigate again from the inlet "
                 "(docs/recovery.md); the figures under \"reshape\". 0 = never")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--reshape-tip-length", o.reshape_tip_length_mm,
                 "with --reshape-tip: the reshaped tip's length, mm (the bent, softer distal part; the wire's own is 6). "
                 "0 = the wire's own")
      ->check(CLI::NonNegativeNumber)
      ->needs(reshape);
  app.add_option("--step-time-limit", o.step_time_limit_s,
                 "end an episode as a timeout when one env step runs longer than this many seconds of wall time (0 = no "
                 "limit, the default: with a limit an outcome can depend on the machine's load; for surfaces where the "
                 "contact solver crawls)")
      ->check(CLI::NonNegativeNumber);
}

}  // namespace gw

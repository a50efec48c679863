#pragma once
// heat.time_scale_factor S (docs/physics.md, "Time-scale factor"): every conductance is
// multiplied by S, so that one second of the run's simulated (compressed) time stands for
// S seconds of real heating time. The outputs give both where they differ: a time in real
// seconds is the simulated time x S, a heat flow rate (W) in real time is the simulated
// one / S. Amounts of heat (J), temperatures and depths are the same in both.
namespace regodem {

struct TimeScale {
  double factor = 1.0;  // S

  double real_time_s(double simulated_s) const { return simulated_s * factor; }
  double real_rate(double simulated_per_s) const { return simulated_per_s / factor; }
  bool compressed() const { return factor != 1.0; }
};

}  // namespace regodem

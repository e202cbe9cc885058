#include "aesim/power/power_model.hpp"

namespace aesim {

PowerResult power(const PowerParams& p, const PowerInputs& in) {
  PowerResult r;
  r.pixel_energy = static_cast<double>(in.firings) * (in.c_int * in.dv_int * p.vdd + p.e_pixel_event);
  r.bus_energy = (static_cast<double>(in.address_ones) + 2.0 * static_cast<double>(in.transactions)) * p.c_bus_line *
                 p.vdd * p.vdd;
  r.receiver_energy = static_cast<double>(in.transactions) * p.e_receiver_event;
  r.static_power = static_cast<double>(in.pixels) * p.p_static_pixel;
  const double dynamic = r.pixel_energy + r.bus_energy + r.receiver_energy;
  r.total_power = (in.duration > 0 ? dynamic / in.duration : 0.0) + r.static_power;
  r.energy_per_event = in.firings ? dynamic / static_cast<double>(in.firings) : 0.0;
  return r;
}

double photocurrent_from_lux(double lux, double responsivity, double efficacy, double pixel_area, double fill_factor) {
  return responsivity * (lux / efficacy) * pixel_area * fill_factor;
}

}  // namespace aesim

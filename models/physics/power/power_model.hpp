#pragma once
#include <cstdint>

namespace aesim {

// Energy and power of an AE imager, from what a run counted. The model (all keys in [power]):
//  - pixel: each firing recharges c_int by dv_int from the supply: E = c_int * dv_int * vdd, plus
//    the comparator's and the pixel logic's switching, e_pixel_event;
//  - bus: every transaction charges and discharges each address line that carries a 1, plus Req
//    and Ack, each a wire of c_bus_line: E = (popcount(address) + 2) * c_bus_line * vdd^2;
//  - receiver: e_receiver_event per transaction it handles;
//  - static: the bias of every pixel's comparator and amplifier, p_static_pixel, all the time.
struct PowerParams {
  double vdd = 3.3;                  // V
  double e_pixel_event = 1e-12;      // J per firing, beyond recharging c_int
  double c_bus_line = 0.5e-12;       // F per bus line (a 32-pixel row or column wire and its pads)
  double e_receiver_event = 10e-12;  // J per bus transaction
  double p_static_pixel = 5.5e-9;    // W per pixel
};

struct PowerInputs {
  double c_int = 0, dv_int = 0;         // F, V
  std::uint64_t firings = 0;            // pixel firings
  std::uint64_t transactions = 0;       // bus transactions (events that took the bus)
  std::uint64_t address_ones = 0;       // total 1 bits over the transactions' addresses
  std::uint64_t pixels = 0;
  double duration = 0;                  // s
};

struct PowerResult {
  double pixel_energy = 0, bus_energy = 0, receiver_energy = 0;  // J over the run
  double static_power = 0;                                       // W
  double total_power = 0;                                        // W
  double energy_per_event = 0;                                   // J of dynamic energy per firing
};

PowerResult power(const PowerParams& p, const PowerInputs& in);

// Photocurrent at illuminance `lux`: responsivity (A/W) x irradiance (lux / luminous efficacy,
// W/m^2) x pixel area (m^2) x fill factor.
double photocurrent_from_lux(double lux, double responsivity, double efficacy, double pixel_area, double fill_factor);

}  // namespace aesim

#pragma once
#include <functional>
#include <vector>

#include "aesim/config/sensor_config.hpp"
#include "aesim/scene/image.hpp"
#include "aesim/scene/scene.hpp"
#include "aesim/run/imager_simulation.hpp"

namespace aesim::testing {

// An image at the array's size with value f(x, y).
inline Image make_image(int width, int height, const std::function<double(int, int)>& f) {
  Image img;
  img.width = width;
  img.height = height;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) img.pixels.push_back(f(x, y));
  }
  return img;
}

inline Scene make_scene(std::vector<Image> frames, double frame_period = 1.0, bool loop = false) {
  Scene s;
  s.source_width = frames.front().width;
  s.source_height = frames.front().height;
  s.frames = std::move(frames);
  s.frame_period = frame_period;
  s.loop = loop;
  return s;
}

// A sensor with the aloha constants but nothing random: no mismatch, reset start, no dark
// current, no reset time, ideal bus. Tests switch on what they examine.
inline SensorConfig exact_sensor(int rows, int cols, int tile) {
  SensorConfig c;
  c.pixel.c_int = 100e-15;
  c.pixel.dv_int = 1.0;
  c.pixel.i_max = 1e-12;
  c.pixel.i_dark = 0;
  c.pixel.t_reset = 0;
  c.pixel.mismatch = 0;
  c.pixel.initial = InitialState::Reset;
  c.array.rows = rows;
  c.array.cols = cols;
  c.array.tile_rows = tile;
  c.array.tile_cols = tile;
  c.bus.access = BusAccess::Ideal;
  c.sim.fidelity = Fidelity::Event;
  return c;
}

// A run that keeps the ground truth of every fired event.
inline SimulationRequest with_truth() {
  SimulationRequest r;
  r.keep_truth = true;
  return r;
}

}  // namespace aesim::testing

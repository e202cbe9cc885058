#include "aesim/classify/template_classifier.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/files/input_path.hpp"
#include "aesim/scene/netpbm.hpp"

namespace aesim {

std::vector<Template> load_templates(const std::string& folder) {
  namespace fs = std::filesystem;
  if (!is_input_folder(folder, "template folder")) throw InputError(fmt::format("template folder '{}' not found", folder));
  std::vector<fs::path> files;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec); !ec && it != fs::directory_iterator(); it.increment(ec)) {
    std::error_code kind;
    if (it->is_regular_file(kind) && file_extension(it->path().string()) == ".pgm") files.push_back(it->path());
  }
  if (ec) throw InputError(fmt::format("template folder '{}': {}", folder, ec.message()));
  std::sort(files.begin(), files.end());
  if (files.size() < 2) throw InputError(fmt::format("template folder '{}' needs at least two .pgm templates", folder));
  std::vector<Template> out;
  for (const fs::path& f : files) {
    const Image img = read_pnm(f.string());
    Template t;
    t.name = f.stem().string();
    t.width = img.width;
    t.height = img.height;
    for (double v : img.pixels) t.white.push_back(v > 0.5 ? 1 : 0);
    t.white_count = static_cast<std::size_t>(std::count(t.white.begin(), t.white.end(), 1));
    if (t.white_count == 0) throw InputError(fmt::format("template '{}' has no white pixel", f.string()));
    for (std::size_t p = 0; p < t.white.size(); ++p) {
      if (!t.white[p]) continue;
      t.centroid_x += static_cast<double>(p % static_cast<std::size_t>(t.width));
      t.centroid_y += static_cast<double>(p / static_cast<std::size_t>(t.width));
    }
    t.centroid_x /= static_cast<double>(t.white_count);
    t.centroid_y /= static_cast<double>(t.white_count);
    if (!out.empty() && (t.width != out.front().width || t.height != out.front().height)) {
      throw InputError(fmt::format("template '{}' is {}x{}, the others {}x{}", f.string(), t.width, t.height,
                                   out.front().width, out.front().height));
    }
    out.push_back(std::move(t));
  }
  std::size_t b_max = 0;
  for (const Template& t : out) b_max = std::max(b_max, t.white_count);
  for (Template& t : out) t.rank = static_cast<double>(b_max) / static_cast<double>(t.white_count);
  return out;
}

Template centred_template(const Template& t) {
  const long dx = std::lround(t.centroid_x - (t.width - 1) / 2.0), dy = std::lround(t.centroid_y - (t.height - 1) / 2.0);
  Template c = t;
  std::fill(c.white.begin(), c.white.end(), 0);
  for (long y = 0; y < t.height; ++y) {
    for (long x = 0; x < t.width; ++x) {
      const long sx = x + dx, sy = y + dy;
      if (sx >= 0 && sy >= 0 && sx < t.width && sy < t.height) {
        c.white[static_cast<std::size_t>(y * t.width + x)] = t.white[static_cast<std::size_t>(sy * t.width + sx)];
      }
    }
  }
  c.white_count = static_cast<std::size_t>(std::count(c.white.begin(), c.white.end(), 1));
  c.centroid_x -= static_cast<double>(dx);
  c.centroid_y -= static_cast<double>(dy);
  return c;
}

std::vector<Containment> contained_templates(const std::vector<Template>& given, double threshold, bool centred) {
  std::vector<Template> templates;
  for (const Template& t : given) templates.push_back(centred ? centred_template(t) : t);
  std::vector<Containment> out;
  for (std::size_t a = 0; a < templates.size(); ++a) {
    for (std::size_t b = 0; b < templates.size(); ++b) {
      if (a == b) continue;
      std::size_t inside = 0;
      for (std::size_t p = 0; p < templates[a].white.size(); ++p) inside += templates[a].white[p] && templates[b].white[p];
      const double fraction =
          templates[a].white_count ? static_cast<double>(inside) / static_cast<double>(templates[a].white_count) : 0.0;
      if (fraction >= threshold) out.push_back({a, b, fraction});
    }
  }
  return out;
}

std::pair<double, double> template_position(std::uint32_t x, std::uint32_t y, int array_width, int array_height,
                                            int template_width, int template_height) {
  const double sx = static_cast<double>(template_width) / std::max(1, array_width);
  const double sy = static_cast<double>(template_height) / std::max(1, array_height);
  return {(x + 0.5) * sx - 0.5, (y + 0.5) * sy - 0.5};
}

RankRecogniser::RankRecogniser(const std::vector<Template>& templates, const ClassifierOptions& options)
    : templates_(templates), options_(options), weight_(templates.size(), 1.0), offset_x_(templates.size(), 0.0),
      offset_y_(templates.size(), 0.0) {
  if (templates_.empty()) throw InputError("the recogniser needs a template");
  const std::size_t n = templates_.size();
  if (options_.ranks) {
    for (std::size_t i = 0; i < n; ++i) weight_[i] = templates_[i].rank;
    r_max_ = *std::max_element(weight_.begin(), weight_.end());
  }
  width_ = templates_.front().width;
  height_ = templates_.front().height;
  // Where each template is read, relative to the (shifted) event.
  if (options_.center_templates) {
    for (std::size_t i = 0; i < n; ++i) {
      offset_x_[i] = templates_[i].centroid_x - (width_ - 1) / 2.0;
      offset_y_[i] = templates_[i].centroid_y - (height_ - 1) / 2.0;
    }
  }
  result_.scores.assign(n, 0.0);
}

void RankRecogniser::centre_on(double mean_x, double mean_y) {
  result_.shift_x = (width_ - 1) / 2.0 - mean_x;
  result_.shift_y = (height_ - 1) / 2.0 - mean_y;
}

bool RankRecogniser::add(double ex, double ey) {
  if (result_.winner >= 0) return true;
  std::vector<double>& score = result_.scores;
  const std::size_t n = score.size();
  ++result_.events_used;
  ++since_restart_;
  for (std::size_t i = 0; i < n; ++i) {
    const long x = std::lround(ex + result_.shift_x + offset_x_[i]), y = std::lround(ey + result_.shift_y + offset_y_[i]);
    if (x < 0 || y < 0 || x >= width_ || y >= height_) continue;
    if (templates_[i].white[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x)]) {
      score[i] += weight_[i];
      ++result_.additions;
    }
  }
  // The best and the second best, then the lead test.
  std::size_t best = 0;
  double second = -1;
  for (std::size_t i = 1; i < n; ++i) {
    ++result_.comparisons;
    if (score[i] > score[best]) {
      second = score[best];
      best = i;
    } else if (score[i] > second) {
      second = score[i];
    }
  }
  ++result_.comparisons;
  if (score[best] - second >= options_.k * r_max_) {
    result_.winner = static_cast<int>(best);
    return true;
  }
  if (*std::max_element(score.begin(), score.end()) > options_.overflow || since_restart_ >= options_.max_events) {
    std::fill(score.begin(), score.end(), 0.0);
    since_restart_ = 0;
    ++result_.restarts;
  }
  return false;
}

ClassifyResult classify(const std::vector<Template>& templates, const std::vector<std::pair<double, double>>& events,
                        const ClassifierOptions& o) {
  RankRecogniser recogniser(templates, o);
  if (o.center_events > 0 && !events.empty()) {
    const std::size_t m = std::min<std::size_t>(o.center_events, events.size());
    double sx = 0, sy = 0;
    for (std::size_t j = 0; j < m; ++j) {
      sx += events[j].first;
      sy += events[j].second;
    }
    recogniser.centre_on(sx / static_cast<double>(m), sy / static_cast<double>(m));
  }
  for (const auto& [x, y] : events) {
    if (recogniser.add(x, y)) break;
  }
  return recogniser.result();
}

}  // namespace aesim

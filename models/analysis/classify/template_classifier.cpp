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
    if (it->is_regular_file(kind) && it->path().extension() == ".pgm") files.push_back(it->path());
  }
  if (ec) throw InputError(fmt::format("template folder '{}': {}", folder, ec.message()));
  std::sort(files.begin(), files.end());
  if (files.size() < 2) throw InputError(fmt::format("template folder '{}' needs at least two .pgm templates", folder));
  std::vector<Template> out;
  for (const fs::path& f : files) {
    const Image img = read_pgm(f.string());
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

ClassifyResult classify(const std::vector<Template>& templates, const std::vector<std::pair<double, double>>& events,
                        const ClassifierOptions& o) {
  ClassifyResult r;
  const std::size_t n = templates.size();
  std::vector<double> weight(n, 1.0);
  double r_max = 1.0;
  if (o.ranks) {
    for (std::size_t i = 0; i < n; ++i) weight[i] = templates[i].rank;
    r_max = *std::max_element(weight.begin(), weight.end());
  }
  const int w = templates.front().width, h = templates.front().height;
  if (o.center_events > 0 && !events.empty()) {
    const std::size_t m = std::min<std::size_t>(o.center_events, events.size());
    double sx = 0, sy = 0;
    for (std::size_t j = 0; j < m; ++j) {
      sx += events[j].first;
      sy += events[j].second;
    }
    r.shift_x = (w - 1) / 2.0 - sx / static_cast<double>(m);
    r.shift_y = (h - 1) / 2.0 - sy / static_cast<double>(m);
  }
  // Where each template is read, relative to the (shifted) event.
  std::vector<double> offset_x(n, 0.0), offset_y(n, 0.0);
  if (o.center_templates) {
    for (std::size_t i = 0; i < n; ++i) {
      offset_x[i] = templates[i].centroid_x - (w - 1) / 2.0;
      offset_y[i] = templates[i].centroid_y - (h - 1) / 2.0;
    }
  }
  std::vector<double> score(n, 0.0);
  std::uint64_t since_restart = 0;
  for (const auto& [ex, ey] : events) {
    ++r.events_used;
    ++since_restart;
    for (std::size_t i = 0; i < n; ++i) {
      const long x = std::lround(ex + r.shift_x + offset_x[i]), y = std::lround(ey + r.shift_y + offset_y[i]);
      if (x < 0 || y < 0 || x >= w || y >= h) continue;
      if (templates[i].white[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)]) {
        score[i] += weight[i];
        ++r.additions;
      }
    }
    // The best and the second best, then the lead test.
    std::size_t best = 0;
    double second = -1;
    for (std::size_t i = 1; i < n; ++i) {
      ++r.comparisons;
      if (score[i] > score[best]) {
        second = score[best];
        best = i;
      } else if (score[i] > second) {
        second = score[i];
      }
    }
    ++r.comparisons;
    if (score[best] - second >= o.k * r_max) {
      r.winner = static_cast<int>(best);
      r.scores = score;
      return r;
    }
    if (*std::max_element(score.begin(), score.end()) > o.overflow || since_restart >= o.max_events) {
      std::fill(score.begin(), score.end(), 0.0);
      since_restart = 0;
      ++r.restarts;
    }
  }
  r.scores = score;
  return r;
}

}  // namespace aesim

#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace aesim {

// A binary template (white = 1) and its rank r = b_max / b, b its number of white pixels.
struct Template {
  std::string name;
  int width = 0, height = 0;
  std::vector<std::uint8_t> white;
  std::size_t white_count = 0;
  double rank = 1;
  double centroid_x = 0, centroid_y = 0;  // of the white pixels
};

// Every .pgm in a folder (pixels above half scale are white), in name order, all of one size,
// ranked among themselves. Throws InputError.
std::vector<Template> load_templates(const std::string& folder);

// A template whose white pixels lie (almost) all inside another's. Under ranks (r = b_max / b) a
// full pass of events over the larger shape gives both b_max, so the larger ties the smaller
// over every pass and can win only by the order of its events.
struct Containment {
  std::size_t inner = 0, outer = 0;  // template indices
  double fraction = 0;               // of the inner template's white pixels inside the outer's
};

// Every pair where at least `threshold` of one template's white pixels are white in another, the
// templates as they are or each shifted (by whole pixels, rounded) to put its centroid at the centre.
std::vector<Containment> contained_templates(const std::vector<Template>& templates, double threshold = 0.95,
                                             bool centred = false);

// The template moved so its centroid lies within half a pixel of the centre (white pixels shifted
// out of the frame are dropped; the rank stays the unshifted template's).
Template centred_template(const Template& t);

struct ClassifierOptions {
  double k = 20.0;  // the winner leads the second by at least k * r_max (20: every clean letter right)
  std::uint64_t max_events = 1000;  // restart when this many events gave no decision
  double overflow = 65535;          // restart when a score exceeds this (a 16-bit accumulator)
  std::uint64_t center_events = 0;  // shift the subject so the centroid of the first N events is centred
  // Compare each template as if shifted so its own centroid is at the centre: the subject, centred
  // by center_events or before it became events, then meets every template on the same footing.
  bool center_templates = false;
  bool ranks = true;                // false: every template adds 1 (plain counting)
};

struct ClassifyResult {
  int winner = -1;                  // index into the templates, or -1 for none
  std::uint64_t events_used = 0;    // events read up to the decision (or all)
  std::uint64_t restarts = 0;
  std::vector<double> scores;       // at the decision (or the end)
  std::uint64_t additions = 0, comparisons = 0;
  double shift_x = 0, shift_y = 0;  // applied by centring
};

// An array pixel's centre in template coordinates, the array scaled onto the templates.
std::pair<double, double> template_position(std::uint32_t x, std::uint32_t y, int array_width, int array_height,
                                            int template_width, int template_height);

// The source paper's rank-weighted recogniser, one event at a time, as firmware runs it: each
// event at (x, y), in template coordinates, adds r_i to every template i white there; after each
// event, if the best score leads the second by at least k * r_max, the best template wins. With
// center_templates, template i is read at the event's position plus (its centroid - the centre),
// to the nearest pixel. `options.center_events` is the caller's to apply (centre_on) before the
// first event: classify() does it from the list, a firmware model from the events it buffered.
class RankRecogniser {
 public:
  // The templates are held by reference and must outlive the recogniser.
  RankRecogniser(const std::vector<Template>& templates, const ClassifierOptions& options);
  // Shifts every later event so that (mean_x, mean_y), the subject's centroid, lies at the centre.
  void centre_on(double mean_x, double mean_y);
  // One event; true once a template has won (later events are ignored).
  bool add(double x, double y);
  const ClassifyResult& result() const { return result_; }
  std::size_t templates() const { return templates_.size(); }

 private:
  const std::vector<Template>& templates_;
  ClassifierOptions options_;
  std::vector<double> weight_, offset_x_, offset_y_;
  double r_max_ = 1.0;
  int width_ = 0, height_ = 0;
  std::uint64_t since_restart_ = 0;
  ClassifyResult result_;
};

// RankRecogniser over a list, centred on its first options.center_events events (if any).
ClassifyResult classify(const std::vector<Template>& templates, const std::vector<std::pair<double, double>>& events,
                        const ClassifierOptions& options);

}  // namespace aesim

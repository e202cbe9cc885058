#include "plan/verification_plan.hpp"

#include <algorithm>
#include <filesystem>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/scene/scene.hpp"
#include "aesim/files/input_path.hpp"
#include "aesim/files/toml_file.hpp"
#include "stimulus/directed_cases.hpp"

namespace aesim {
namespace {

namespace fs = std::filesystem;

VerificationPlan builtin(const std::string& name, int seeds, double firings) {
  VerificationPlan p;
  p.name = name;
  struct Load {
    double g, ready;
  };
  for (const Load l : {Load{0.05, 1.0}, Load{0.3, 0.9}, Load{1.0, 0.6}}) {
    for (int s = 1; s <= seeds; ++s) p.scenes.push_back({default_scene_path(), l.g, static_cast<std::uint64_t>(s), firings, l.ready});
  }
  return p;
}

VerificationPlan read_plan(const std::string& path) {
  const std::string label = fmt::format("plan '{}'", path);
  if (!is_input_file(path, "plan")) throw InputError(fmt::format("--plan: '{}' is not quick, full or a plan file", path));
  const TomlValue root = parse_toml_file(path, label);
  auto fail = [&](const std::string& key, const std::string& what) -> void {
    throw InputError(fmt::format("{}: {}: {}", label, key, what));
  };
  VerificationPlan p;
  p.name = path;
  for (const auto& [key, value] : root.as_table()) {
    if (key == "directed") {
      if (value.is_boolean()) {
        p.directed = value.as_boolean();
        continue;
      }
      // A list names the directed cases to run.
      if (!value.is_array()) fail(key, "expected true, false or a list of directed case names");
      ReceiverDescription any;
      any.clock_hz = 1e6;
      any.ack_latency_min = any.ack_latency_max = 1;
      std::vector<std::string> known;
      for (const VerifyCase& c : directed_cases(any)) known.push_back(c.name);
      for (const TomlValue& name : value.as_array()) {
        if (!name.is_string() || std::find(known.begin(), known.end(), name.as_string()) == known.end()) {
          fail(key, fmt::format("not a directed case (one of {})", fmt::join(known, ", ")));
        }
        p.directed_cases.push_back(name.as_string());
      }
    } else if (key == "formal") {
      if (!value.is_boolean()) fail(key, "expected true or false");
      p.formal = value.as_boolean();
    } else if (key != "scene") {
      fail(key, "unknown key (directed, formal, [[scene]])");
    }
  }
  const auto& tables = root.as_table();
  const auto it = tables.find("scene");
  if (it == tables.end()) return p;
  if (!it->second.is_array()) fail("scene", "expected [[scene]] tables");
  const fs::path dir = fs::path(path).parent_path();
  for (std::size_t i = 0; i < it->second.as_array().size(); ++i) {
    const TomlValue& t = it->second.as_array()[i];
    const std::string at = fmt::format("scene[{}]", i);
    if (!t.is_table()) fail(at, "expected a table");
    SceneLoad base;
    base.scene = default_scene_path();
    std::vector<std::uint64_t> seeds = {1};
    for (const auto& entry : t.as_table()) {
      const std::string& key = entry.first;
      const TomlValue& v = entry.second;
      const std::string k = at + "." + key;
      auto number = [&](double lo, double hi) {
        const double x = v.is_integer() ? static_cast<double>(v.as_integer()) : v.is_floating() ? v.as_floating() : -1e300;
        if (!(x >= lo && x <= hi)) fail(k, fmt::format("expected a number from {} to {}", lo, hi));
        return x;
      };
      if (key == "file") {
        if (!v.is_string()) fail(k, "expected a path");
        const fs::path f(v.as_string());
        base.scene = (f.is_absolute() ? f : dir / f).string();
      } else if (key == "load") {
        base.load = number(1e-4, 10);
      } else if (key == "firings") {
        base.firings = number(1, 1e8);
      } else if (key == "ready") {
        base.ready = number(0.01, 1);
      } else if (key == "seeds") {
        seeds.clear();
        if (v.is_integer()) {
          const double n = number(1, 1000);
          for (int s = 1; s <= static_cast<int>(n); ++s) seeds.push_back(static_cast<std::uint64_t>(s));
        } else if (v.is_array()) {
          for (const TomlValue& s : v.as_array()) {
            if (!s.is_integer() || s.as_integer() < 0) fail(k, "expected non-negative integers");
            seeds.push_back(static_cast<std::uint64_t>(s.as_integer()));
          }
          if (seeds.empty() || seeds.size() > 1000) fail(k, "expected 1 to 1000 seeds");
        } else {
          fail(k, "expected a count or a list of seeds");
        }
      } else {
        fail(k, "unknown key (file, load, seeds, firings, ready)");
      }
    }
    for (std::uint64_t s : seeds) {
      SceneLoad l = base;
      l.seed = s;
      p.scenes.push_back(l);
    }
  }
  return p;
}

}  // namespace

VerificationPlan make_plan(const std::string& plan) {
  if (plan == "quick") return builtin("quick", 2, 2000);
  if (plan == "full") return builtin("full", 4, 300000);
  return read_plan(plan);
}

std::vector<VerifyCase> plan_cases(const VerificationPlan& plan, const ReceiverDescription& d, std::uint64_t seed,
                                   std::vector<std::string>* notes) {
  const bool ready = d.has("ready");
  std::vector<VerifyCase> cases;
  std::vector<std::string> left_out, left_out_reset, left_out_glitch;
  if (plan.directed) {
    for (VerifyCase& c : directed_cases(d)) {
      const auto& only = plan.directed_cases;
      if (!only.empty() && std::find(only.begin(), only.end(), c.name) == only.end()) continue;
      if (!ready && !c.stalls.empty()) {
        left_out.push_back(c.name);
        continue;
      }
      if (!d.has_reset() && c.reset_after_ack > 0) {
        left_out_reset.push_back(c.name);
        continue;
      }
      if (d.two_phase() && !c.glitches.empty()) {
        left_out_glitch.push_back(c.name);
        continue;
      }
      cases.push_back(std::move(c));
    }
  }
  if (notes && !d.has_reset()) {
    std::string note = "the receiver has no reset: every case starts from the design's initial values";
    if (!left_out_reset.empty()) note += fmt::format(", and the cases {} are left out", fmt::join(left_out_reset, ", "));
    notes->push_back(note);
  }
  if (notes && !left_out_glitch.empty()) {
    notes->push_back(fmt::format("the link is two-phase, where every change of Req is an event and none is withdrawn: "
                                 "the cases {} are left out",
                                 fmt::join(left_out_glitch, ", ")));
  }
  bool always_ready = false;
  for (SceneLoad l : plan.scenes) {
    l.seed += seed - 1;
    if (!ready && l.ready < 1) {
      l.ready = 1;
      always_ready = true;
    }
    cases.push_back(scene_case(l, d));
  }
  if (notes && (!left_out.empty() || always_ready)) {
    std::string note = "the receiver has no ready port, so it takes no back-pressure:";
    if (!left_out.empty()) note += fmt::format(" the cases {} are left out", fmt::join(left_out, ", "));
    if (!left_out.empty() && always_ready) note += " and";
    if (always_ready) note += " the scene runs' consumer is always ready";
    notes->push_back(note);
  }
  if (cases.empty()) throw InputError(fmt::format("plan '{}' has no case to run", plan.name));
  return cases;
}

double plan_cycles(const std::vector<VerifyCase>& cases) {
  double cycles = 0;
  for (const VerifyCase& c : cases) cycles += static_cast<double>(c.max_edges);
  return cycles;
}

}  // namespace aesim

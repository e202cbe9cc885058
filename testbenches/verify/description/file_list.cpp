#include "description/file_list.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/files/input_file.hpp"

namespace aesim {
namespace {

namespace fs = std::filesystem;

constexpr int kMostNested = 8;
constexpr std::uintmax_t kMostListBytes = 1 << 20;

class ListReader {
 public:
  ListReader(FileList& out, const std::string& label) : out_(out), label_(label) {}

  void read(const std::string& path, int depth) {
    const std::string identity = fs::weakly_canonical(path, ec_).string();
    if (std::find(open_.begin(), open_.end(), identity) != open_.end()) fail(path, 0, "it names itself (a loop of lists)");
    if (depth >= kMostNested) fail(path, 0, fmt::format("lists nested more than {} deep", kMostNested));
    open_.push_back(identity);
    const std::string text = without_block_comments(read_input_file(path, label_, kMostListBytes));
    const fs::path folder = fs::path(path).parent_path();
    std::istringstream lines(text);
    std::string line;
    for (int number = 1; std::getline(lines, line); ++number) {
      for (const char* comment : {"//", "#"}) {
        if (const auto at = line.find(comment); at != std::string::npos) line.resize(at);
      }
      std::istringstream words(line);
      std::string word;
      while (words >> word) {
        word = expanded(word, path, number);
        if (word.rfind("+incdir+", 0) == 0) {
          for (const std::string& dir : plus_separated(word.substr(8))) out_.include_dirs.push_back(resolved(dir, folder));
        } else if (word.rfind("+define+", 0) == 0) {
          for (const std::string& def : plus_separated(word.substr(8))) {
            const auto eq = def.find('=');
            out_.defines[def.substr(0, eq)] = eq == std::string::npos ? "" : def.substr(eq + 1);
          }
        } else if (word == "-f" || word == "-F" || word == "-v") {
          std::string operand;
          if (!(words >> operand)) fail(path, number, fmt::format("{} names no file", word));
          operand = resolved(expanded(operand, path, number), folder);
          if (word == "-v") {
            out_.sources.push_back(operand);
          } else {
            read(operand, depth + 1);
          }
        } else if (word[0] == '-' || word[0] == '+') {
          fail(path, number, fmt::format("'{}' asks the simulator for something aesim does not pass on: give the "
                                         "sources, +incdir+ and +define+ only (-y library folders as their files)",
                                         word));
        } else {
          out_.sources.push_back(resolved(word, folder));
        }
      }
    }
    open_.pop_back();
  }

 private:
  [[noreturn]] void fail(const std::string& path, int line, const std::string& why) const {
    throw InputError(line > 0 ? fmt::format("{}: file list '{}' line {}: {}", label_, path, line, why)
                              : fmt::format("{}: file list '{}': {}", label_, path, why));
  }
  // /* ... */ comments blanked out, their line breaks kept so that line numbers stay true.
  static std::string without_block_comments(std::string text) {
    for (std::size_t at = text.find("/*"); at != std::string::npos; at = text.find("/*", at)) {
      const std::size_t end = text.find("*/", at + 2);
      const std::size_t stop = end == std::string::npos ? text.size() : end + 2;
      for (std::size_t i = at; i < stop; ++i) {
        if (text[i] != '\n') text[i] = ' ';
      }
      at = stop;
    }
    return text;
  }
  static std::vector<std::string> plus_separated(const std::string& text) {
    std::vector<std::string> parts;
    std::string part;
    std::istringstream in(text);
    while (std::getline(in, part, '+')) {
      if (!part.empty()) parts.push_back(part);
    }
    return parts;
  }
  static std::string resolved(const std::string& p, const fs::path& folder) {
    const fs::path path(p);
    return (path.is_absolute() ? path : folder / path).lexically_normal().string();
  }
  // $VAR and ${VAR} from the environment; one that is not set is an error, not an empty string
  // (a path that lost its root would name some other file).
  std::string expanded(const std::string& word, const std::string& path, int line) const {
    std::string out;
    for (std::size_t i = 0; i < word.size();) {
      if (word[i] != '$') {
        out += word[i++];
        continue;
      }
      const bool braced = i + 1 < word.size() && word[i + 1] == '{';
      std::size_t j = i + (braced ? 2 : 1);
      const std::size_t start = j;
      while (j < word.size() && (std::isalnum(static_cast<unsigned char>(word[j])) || word[j] == '_')) ++j;
      const std::string name = word.substr(start, j - start);
      if (name.empty() || (braced && (j >= word.size() || word[j] != '}'))) {
        fail(path, line, fmt::format("'{}' is no $VAR or ${{VAR}}", word));
      }
      const char* value = std::getenv(name.c_str());
      if (!value) fail(path, line, fmt::format("environment variable {} is not set", name));
      out += value;
      i = j + (braced ? 1 : 0);
    }
    return out;
  }

  FileList& out_;
  std::string label_;
  std::vector<std::string> open_;
  std::error_code ec_;
};

}  // namespace

FileList read_file_list(const std::string& path, const std::string& label) {
  FileList out;
  ListReader(out, label).read(path, 0);
  return out;
}

}  // namespace aesim

#include "aesim/event_files/forked_reader.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <stdexcept>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/files/descriptor_io.hpp"
#include "aesim/process/child_process.hpp"

namespace aesim {
namespace {

// The isolated reader's answer on its pipe: a byte, 0 then the recording or 1 then an error.
void write_all(int fd, const void* data, std::size_t size) {
  if (write_fully(fd, data, size) != 0) throw std::runtime_error("pipe closed");
}
void write_text(int fd, const std::string& text) {
  const std::uint32_t n = static_cast<std::uint32_t>(text.size());
  write_all(fd, &n, sizeof n);
  write_all(fd, text.data(), n);
}
void send_recording(int fd, const std::string& path, const std::function<PolarityRecording()>& read) {
  PolarityRecording rec;
  std::string error;
  try {
    rec = read();
  } catch (const InputError& e) {
    error = e.what();
  } catch (const std::exception& e) {
    error = fmt::format("event file '{}': reading it failed: {}", path, e.what());
  }
  const std::uint8_t failed = error.empty() ? 0 : 1;
  write_all(fd, &failed, 1);
  if (failed) return write_text(fd, error);
  const std::int32_t size[2] = {rec.width, rec.height};
  const std::uint64_t n = rec.events.size();
  write_all(fd, size, sizeof size);
  write_all(fd, &n, sizeof n);
  write_all(fd, rec.events.data(), n * sizeof(PolarityEvent));
  write_all(fd, &rec.reordered, sizeof rec.reordered);
  const std::uint32_t notes = static_cast<std::uint32_t>(rec.notes.size());
  write_all(fd, &notes, sizeof notes);
  for (const std::string& note : rec.notes) write_text(fd, note);
  const std::uint32_t read_as = static_cast<std::uint32_t>(rec.read_as.size());
  write_all(fd, &read_as, sizeof read_as);
  for (const std::string& r : rec.read_as) write_text(fd, r);
  const std::uint32_t keys = static_cast<std::uint32_t>(rec.sensor.size());
  write_all(fd, &keys, sizeof keys);
  for (const auto& [key, value] : rec.sensor) {
    write_text(fd, key);
    write_text(fd, value);
  }
}

bool read_all(int fd, void* data, std::size_t size) {
  return read_fully(fd, data, size) == static_cast<ssize_t>(size);
}
bool read_text(int fd, std::string& text) {
  std::uint32_t n = 0;
  if (!read_all(fd, &n, sizeof n) || n > (1u << 20)) return false;
  text.resize(n);
  return read_all(fd, text.data(), n);
}

// The recording from the pipe; false when the reader stopped before the end of its answer.
bool receive_recording(int fd, PolarityRecording& rec, std::string& error) {
  std::uint8_t failed = 0;
  if (!read_all(fd, &failed, 1)) return false;
  if (failed) return read_text(fd, error);
  std::int32_t size[2] = {};
  std::uint64_t n = 0;
  if (!read_all(fd, size, sizeof size) || !read_all(fd, &n, sizeof n) || n > (std::uint64_t(1) << 32)) return false;
  rec.width = size[0];
  rec.height = size[1];
  // Grown as the bytes arrive, so a reader that dies mid-answer costs no more than it sent.
  constexpr std::uint64_t kChunk = std::uint64_t(1) << 20;
  for (std::uint64_t have = 0; have < n;) {
    const std::uint64_t take = std::min(kChunk, n - have);
    rec.events.resize(have + take);
    if (!read_all(fd, rec.events.data() + have, take * sizeof(PolarityEvent))) return false;
    have += take;
  }
  std::uint32_t notes = 0;
  if (!read_all(fd, &rec.reordered, sizeof rec.reordered) || !read_all(fd, &notes, sizeof notes) || notes > 64) {
    return false;
  }
  rec.notes.resize(notes);
  for (std::string& note : rec.notes) {
    if (!read_text(fd, note)) return false;
  }
  std::uint32_t read_as = 0;
  if (!read_all(fd, &read_as, sizeof read_as) || read_as > 64) return false;
  rec.read_as.resize(read_as);
  for (std::string& r : rec.read_as) {
    if (!read_text(fd, r)) return false;
  }
  std::uint32_t keys = 0;
  if (!read_all(fd, &keys, sizeof keys)) return false;
  for (std::uint32_t k = 0; k < keys; ++k) {
    std::string key, value;
    if (!read_text(fd, key) || !read_text(fd, value)) return false;
    rec.sensor[key] = value;
  }
  return true;
}

}  // namespace

PolarityRecording read_in_forked_copy(const std::string& path, const char* library,
                                      const std::function<PolarityRecording()>& read) {
  // A real recording needs memory in proportion to its size (a compressed column of 8-byte
  // numbers, decompressed, then the events made of it: tens of bytes per byte read); a corrupt
  // header can claim any size (a 142-byte .mat made matio fill 1 GB).
  std::error_code ec;
  const std::uint64_t file_bytes = std::filesystem::file_size(path, ec);
  const std::uint64_t budget = (std::uint64_t(256) << 20) + 64 * (ec ? 0 : file_bytes);
  const IsolatedWork reader = fork_isolated([&](int fd) {
    limit_memory_growth(budget);
    send_recording(fd, path, read);
  });
  PolarityRecording rec;
  std::string error;
  const bool complete = receive_recording(reader.fd, rec, error);
  ::close(reader.fd);
  const int status = wait_child(reader.pid);
  if (complete && status == 0) {
    if (!error.empty()) throw InputError(error);
    return rec;
  }
  if (status > 128) {
    throw InputError(fmt::format("event file '{}': {} crashed reading it (signal {}); the file is corrupt", path, library,
                                 status - 128));
  }
  throw InputError(fmt::format("event file '{}': the {} reader stopped (status {}) before it finished", path, library, status));
}

}  // namespace aesim

// A small, explicit timing harness: warm up, time N runs one at a time, report the median.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <sched.h>

namespace rle_vision {
namespace bench {

// Runs `body` `warmup` times untimed, then `runs` times timed; returns the median in ms.
template <typename Body>
double medianMs(Body body, int runs = 400, int warmup = 30) {
  for (int i = 0; i < warmup; ++i) body();
  std::vector<double> ms(runs);
  for (int i = 0; i < runs; ++i) {
    const auto start = std::chrono::steady_clock::now();
    body();
    ms[i] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
  std::nth_element(ms.begin(), ms.begin() + runs / 2, ms.end());
  return ms[runs / 2];
}

// Runs the bodies in turns, `per_turn` timed runs of each (after one untimed, so each turn
// starts warm, as a repeated body does), until each has `runs`; returns each body's median in
// ms. A machine's speed drifts over seconds: bodies timed in the same turns feel the same
// drift, so the ratios of their medians hold where medians timed one after another wander.
template <typename Body>
std::vector<double> medianMsInTurns(const std::vector<Body>& bodies, int runs = 400, int per_turn = 10) {
  std::vector<std::vector<double>> ms(bodies.size());
  for (int done = 0; done < runs; done += per_turn) {
    for (size_t k = 0; k < bodies.size(); ++k) {
      bodies[k]();
      for (int i = 0; i < per_turn; ++i) {
        const auto start = std::chrono::steady_clock::now();
        bodies[k]();
        ms[k].push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
      }
    }
  }
  std::vector<double> medians;
  for (std::vector<double>& times : ms) {
    std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
    medians.push_back(times[times.size() / 2]);
  }
  return medians;
}

// Keeps the compiler from dropping work whose result is unused.
template <typename T>
inline void keep(const T& value) {
  asm volatile("" : : "g"(&value) : "memory");
}

// True when a command-line value is a whole number of 1 to max_digits digits (a label class).
inline bool isWholeNumber(const std::string& text, size_t max_digits) {
  return !text.empty() && text.size() <= max_digits && text.find_first_not_of("0123456789") == std::string::npos;
}

// True when the whole of a command-line value is one finite number (into `value`).
inline bool isFiniteNumber(const char* text, double* value) {
  char* end = nullptr;
  *value = std::strtod(text, &end);
  return end != text && *end == '\0' && std::isfinite(*value);
}

// Pins the calling thread (and the threads it starts after) to CPU `cpu`.
inline void pinToCpu(int cpu) {
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(cpu, &set);
  sched_setaffinity(0, sizeof(set), &set);
}

// Pins the process to one CPU so one-thread figures are one-core figures.
inline void pinToOneCpu() { pinToCpu(0); }

// The CPU's model name (results files say where they were measured).
inline std::string machineName() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  }
  return "unknown";
}

// Today's date, UTC, as YYYY-MM-DD.
inline std::string todayUtc() {
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof(date), "%Y-%m-%d", std::gmtime(&now));
  return date;
}

// Writes a flat JSON object of numbers, after the machine and the date it was measured on
// (scripts/readme_figures.py prints both under the README's tables).
inline void writeJson(const std::string& path, const std::vector<std::pair<std::string, double>>& values) {
  std::ofstream out(path);
  out << "{\n  \"machine\": \"" << machineName() << "\",\n  \"date\": \"" << todayUtc() << "\",\n";
  for (size_t i = 0; i < values.size(); ++i) {
    char number[64];
    std::snprintf(number, sizeof(number), "%.6g", values[i].second);
    out << "  \"" << values[i].first << "\": " << number << (i + 1 < values.size() ? ",\n" : "\n");
  }
  out << "}\n";
}

}  // namespace bench
}  // namespace rle_vision

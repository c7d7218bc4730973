// The machine bench measures on, and how busy other work kept it.
#include "app/bench_conditions.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <sys/resource.h>
#include <unistd.h>

#include "core/parallel.h"
#include "rasterizer/rasterizer.h"
#include "raytracer_ref/reference.h"

namespace rc::app {

std::string cpuDescription(const std::string& cpuinfo, const std::vector<CpuCache>& caches) {
  // The fields of the first processor block, values trimmed.
  std::map<std::string, std::string> field;
  std::istringstream in(cpuinfo);
  for (std::string line; std::getline(in, line) && !line.empty();) {
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    const std::string key = line.substr(0, colon), rest = line.substr(colon + 1);
    const std::size_t keyEnd = key.find_last_not_of(" \t"), start = rest.find_first_not_of(" \t");
    if (keyEnd == std::string::npos) continue;
    field.emplace(key.substr(0, keyEnd + 1), start == std::string::npos ? "" : rest.substr(start));
  }
  const auto value = [&](const char* key) {
    const auto it = field.find(key);
    return it == field.end() ? std::string() : it->second;
  };
  std::string cpu = value("model name");
  if (cpu.empty()) cpu = "unknown";
  // The model name alone can be a family's (a virtual machine's "AMD EPYC"): the numbers tell
  // its generations apart.
  std::vector<std::string> details;
  if (!value("cpu family").empty() && !value("model").empty()) {
    std::string id = "family " + value("cpu family") + ", model " + value("model");
    if (!value("stepping").empty()) id += ", stepping " + value("stepping");
    details.push_back(id);
  }
  std::string sizes;
  for (const CpuCache& cache : caches) sizes += (sizes.empty() ? "" : ", ") + cache.name + " " + cache.size;
  if (!sizes.empty()) details.push_back(sizes);
  for (std::size_t i = 0; i < details.size(); ++i) cpu += (i == 0 ? " (" : "; ") + details[i];
  return details.empty() ? cpu : cpu + ")";
}

namespace {

// The data and unified caches of CPU 0 as sysfs lists them, by level: "L1d", "L2", "L3".
// A file's first line; empty where it cannot be read (a kernel file absent on this machine).
std::string firstLine(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string text;
  std::getline(in, text);
  return text;
}

std::vector<CpuCache> cpu0Caches() {
  std::vector<CpuCache> caches;
  for (int index = 0;; ++index) {
    const std::filesystem::path dir = "/sys/devices/system/cpu/cpu0/cache/index" + std::to_string(index);
    const std::string level = firstLine(dir / "level"), type = firstLine(dir / "type"), size = firstLine(dir / "size");
    if (level.empty()) break;
    if (type == "Instruction" || size.empty()) continue;
    caches.push_back({"L" + level + (type == "Data" ? "d" : ""), size});
  }
  return caches;
}

}  // namespace

BenchMachine benchMachine() {
  BenchMachine m;
  std::ifstream cpuinfo("/proc/cpuinfo");
  m.cpu = cpuDescription(std::string(std::istreambuf_iterator<char>(cpuinfo), {}), cpu0Caches());
  m.logicalCpus = resolveThreadCount(0);
  m.widestKernelIsa = kernelIsaName(resolveKernelIsa(KernelIsa::kAuto));
  m.fastestEmbreeIsa = fastestEmbreeIsa();
#if defined(__clang__)
  m.compiler = "clang " __clang_version__;
#else
  m.compiler = "GCC " __VERSION__;
#endif
  m.embree = embreeVersion();
  m.rastercheck = RASTERCHECK_VERSION;
  return m;
}

std::string describeHardware(const BenchMachine& m) {
  return m.cpu + ", " + std::to_string(m.logicalCpus) + " logical CPU" + (m.logicalCpus == 1 ? "" : "s") +
         " (kernels up to " + m.widestKernelIsa + ", Embree " + m.fastestEmbreeIsa + ")";
}

std::string describeBuilds(const BenchMachine& m) {
  return m.compiler + ", Embree " + m.embree + ", rastercheck " + m.rastercheck;
}

std::string describe(const BenchMachine& m) { return describeHardware(m) + "; " + describeBuilds(m); }

std::optional<CpuTimes> parseProcStat(const std::string& text) {
  std::istringstream in(text);
  std::string label;
  if (!(in >> label) || label != "cpu") return std::nullopt;
  // user nice system idle iowait irq softirq steal (guest and guest_nice, after them, are
  // already counted in user and nice); older kernels stop after idle, or before steal.
  double field[8] = {};
  int count = 0;
  while (count < 8 && in >> field[count]) ++count;
  if (count < 4) return std::nullopt;
  CpuTimes t;
  t.busy = field[0] + field[1] + field[2] + field[5] + field[6];
  t.steal = field[7];
  for (const double f : field) t.total += f;
  return t;
}

BenchLoad loadBetween(const CpuTimes& before, const CpuTimes& after, double ownTicks) {
  const double total = after.total - before.total;
  if (!(total > 0)) return {};
  // The kernel counts in ticks and this process's own time more finely: clamped.
  const auto share = [&](double ticks) { return std::clamp(ticks / total, 0.0, 1.0); };
  return {share(after.busy - before.busy - ownTicks), share(after.steal - before.steal)};
}

namespace {

// This process's CPU time, all its threads, in /proc/stat's ticks.
double ownTicks() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
  return (seconds(usage.ru_utime) + seconds(usage.ru_stime)) * double(sysconf(_SC_CLK_TCK));
}

}  // namespace

LoadMeter::LoadMeter() : start_(parseProcStat(firstLine("/proc/stat"))), ownStart_(ownTicks()) {}

std::optional<BenchLoad> LoadMeter::load() const {
  const std::optional<CpuTimes> now = parseProcStat(firstLine("/proc/stat"));
  if (!start_ || !now) return std::nullopt;
  return loadBetween(*start_, *now, ownTicks() - ownStart_);
}

std::string percentOf(double share) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f%%", 100 * share);
  return text;
}

std::string describe(const BenchLoad& load) {
  return "other processes used " + percentOf(load.others) + " of the CPUs' time, the hypervisor's other guests " +
         percentOf(load.steal) + " (steal)";
}

std::string busyNote(const BenchLoad& load) {
  constexpr double kBusy = 0.05;
  return load.others + load.steal > kBusy ? "a busy machine, so slower and noisier figures than an idle one gives" : "";
}

}  // namespace rc::app

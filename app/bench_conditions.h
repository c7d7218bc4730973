// The conditions bench's figures were measured under: the machine (its CPU, its instruction
// sets, the builds) and how busy other work kept it.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace rc::app {

// A cache of a CPU: "L1d", "L2", "L3", and its size as sysfs writes it ("1024K").
struct CpuCache {
  std::string name, size;
};
// The CPU as the text of /proc/cpuinfo names its first processor, with its caches:
// "AMD EPYC (family 26, model 2, stepping 1; L1d 48K, L2 1024K, L3 32768K)". The model name
// alone ("unknown" where there is none) can be a whole family's in a virtual machine; the
// family, model and stepping tell its generations apart, and the caches say what fits.
std::string cpuDescription(const std::string& cpuinfo, const std::vector<CpuCache>& caches);

// What the figures were measured on: the CPU (cpuDescription of this machine), its logical
// CPUs, the widest kernels and the fastest Embree mode it runs, and the builds of the
// compiler, Embree and rastercheck.
struct BenchMachine {
  std::string cpu;
  int logicalCpus = 0;
  std::string widestKernelIsa, fastestEmbreeIsa, compiler, embree, rastercheck;
};
BenchMachine benchMachine();
// One line: "AMD EPYC (...), 2 logical CPUs (kernels up to avx512, Embree avx512); GCC 12.2.0, ...",
// its hardware and its builds, which the two functions after it give apart.
std::string describe(const BenchMachine& machine);
std::string describeHardware(const BenchMachine& machine);  // "AMD EPYC (...), 2 logical CPUs (...)"
std::string describeBuilds(const BenchMachine& machine);    // "GCC 12.2.0, Embree 3.13.5, rastercheck 0.1.0"

// How busy the machine was with other work while bench ran: the shares of all its CPUs' time
// that other processes used, and that the hypervisor gave to other guests (steal). Figures
// taken on a busy machine are slower and noisier than on an idle one; these say so.
struct BenchLoad {
  double others = 0, steal = 0;  // 0 to 1
};
// The machine's CPU time as the first line of /proc/stat counts it, in its ticks: busy (user,
// nice, system, irq, softirq), steal, and all of it (idle and iowait too). Nothing where the
// text has no such line.
struct CpuTimes {
  double busy = 0, steal = 0, total = 0;
};
std::optional<CpuTimes> parseProcStat(const std::string& text);
// The load between two readings of /proc/stat, during which this process itself used
// `ownTicks` of CPU time (which is not the others').
BenchLoad loadBetween(const CpuTimes& before, const CpuTimes& after, double ownTicks);
// Reads /proc/stat and this process's CPU time when made, and the load since when asked;
// nothing where /proc/stat cannot be read.
class LoadMeter {
 public:
  LoadMeter();
  std::optional<BenchLoad> load() const;

 private:
  std::optional<CpuTimes> start_;
  double ownStart_ = 0;
};
// "other processes used 0.4% of the CPUs' time, the hypervisor's other guests 0.0% (steal)"
std::string describe(const BenchLoad& load);
std::string percentOf(double share);  // 0.004: "0.4%"
// Where other work and steal took more than 5% of the CPUs' time, enough to slow the figures
// and spread them: "a busy machine, so slower and noisier figures than an idle one gives";
// else nothing.
std::string busyNote(const BenchLoad& load);

}  // namespace rc::app

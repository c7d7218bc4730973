// bench's rows written as JSON and CSV, and the JSON read back.
#include "app/bench_files.h"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "compare/report.h"
#include "core/error.h"

namespace rc::app {

std::string benchJson(const std::vector<BenchRow>& rows, const BenchMachine& machine, const std::optional<BenchLoad>& load) {
  nlohmann::json list = nlohmann::json::array();
  for (const BenchRow& r : rows) {
    nlohmann::json row = {{"scene", r.scene}, {"triangles", r.triangles}, {"width", r.width}, {"height", r.height},
                          {"threads", r.threads}, {"setting", r.setting}, {"default", r.isDefault}, {"runs", r.runs},
                          {"raster_ms", r.rasterMs}, {"raster_ms_min", r.rasterMsMin}, {"raster_ms_max", r.rasterMsMax},
                          {"store_floor_ms", r.storeFloorMs},
                          {"stage_ms", {{"transform", r.transformMs}, {"setup", r.setupMs}, {"bin", r.binMs},
                                        {"tiles", r.tilesMs}}},
                          {"raster_isa", r.rasterIsa}, {"diagnostics", r.diagnostics}, {"cull", r.cull},
                          {"reference_isa", r.referenceIsa}, {"reference_build", r.referenceBuild},
                          {"reference_build_ms", r.referenceBuildMs}, {"reference_trace_ms", r.referenceTraceMs},
                          {"speedup", r.speedup}, {"speedup_min", r.speedupMin}, {"speedup_max", r.speedupMax},
                          {"speedup_with_build", r.speedupWithBuild},
                          {"speedup_with_build_quality", r.speedupWithBuildQuality},
                          {"triangles_per_second", r.trianglesPerSecond}, {"pixels_per_second", r.pixelsPerSecond},
                          {"bary_max_error", r.baryMax}, {"bary_p999_error", r.baryP999},
                          {"disagreement_fraction", r.disagreementFraction},
                          {"coverage_fraction", r.coverageFraction}};
    if (r.exrWriteMs >= 0) row["exr_write_ms"] = r.exrWriteMs;
    if (r.load) row["load"] = {{"other_processes", r.load->others}, {"steal", r.load->steal}};
    if (r.overDefault > 0) {
      row["raster_over_default"] = r.overDefault;
      row["raster_over_default_min"] = r.overDefaultMin;
      row["raster_over_default_max"] = r.overDefaultMax;
    }
    nlohmann::json builds = nlohmann::json::array();
    for (const BenchRow::ReferenceBuild& b : r.referenceBuilds) {
      builds.push_back({{"build", b.build}, {"build_ms", b.buildMs}, {"trace_ms", b.traceMs}});
    }
    row["reference_builds"] = builds;
    row["raster_ms_runs"] = r.rasterRuns;
    row["reference_trace_ms_runs"] = r.traceRuns;
    row["stage_ms_runs"] = {{"transform", r.transformRuns}, {"setup", r.setupRuns}, {"bin", r.binRuns},
                            {"tiles", r.tilesRuns}};
    list.push_back(row);
  }
  const nlohmann::json about = {{"cpu", machine.cpu},
                                {"logical_cpus", machine.logicalCpus},
                                {"widest_kernel_isa", machine.widestKernelIsa},
                                {"fastest_embree_isa", machine.fastestEmbreeIsa},
                                {"compiler", machine.compiler},
                                {"embree", machine.embree},
                                {"rastercheck", machine.rastercheck}};
  nlohmann::json doc = {{"format_version", 1}, {"machine", about}};
  if (load) doc["load"] = {{"other_processes", load->others}, {"steal", load->steal}};
  doc["rows"] = list;
  return jsonDocument(doc);
}

namespace {

// A load as benchJson writes it, at `at` (the file and the JSON pointer): each share a number
// from 0 to 1, as loadBetween gives it.
BenchLoad readLoad(const nlohmann::json& j, const std::string& at) {
  const auto share = [&](const char* field) {
    if (!j.is_object() || !j.contains(field) || !j[field].is_number()) {
      throw badInput(at + "/" + field, "missing, or not a number");
    }
    const double value = j[field].get<double>();
    if (!(value >= 0 && value <= 1)) {
      throw badInput(at + "/" + field, "is " + formatNumber(value) + "; must be a share from 0 to 1");
    }
    return value;
  };
  return {share("other_processes"), share("steal")};
}

// What `read` returns, a missing or mistyped field (nlohmann's exception) refused at `at`.
template <class Read>
auto readFields(const std::string& at, const Read& read) {
  try {
    return read();
  } catch (const nlohmann::json::exception& e) {
    throw badInput(at, std::string("missing or mistyped field: ") + e.what());
  }
}

// One row as benchJson writes it, at `at` (the file and the JSON pointer): the fields the
// report and the chart use, each checked for its type, and the ones placed on log axes for range.
BenchRow readRow(const nlohmann::json& j, const std::string& at) {
  return readFields(at, [&] {
    BenchRow r;
    r.scene = j.at("scene").get<std::string>();
    r.setting = j.at("setting").get<std::string>();
    r.isDefault = j.at("default").get<bool>();
    r.triangles = j.at("triangles").get<std::size_t>();
    r.width = j.at("width").get<int>();
    r.height = j.at("height").get<int>();
    r.threads = j.at("threads").get<int>();
    r.runs = j.value("runs", 0);
    r.rasterMs = j.at("raster_ms").get<double>();
    r.storeFloorMs = j.value("store_floor_ms", 0.0);
    r.rasterIsa = j.value("raster_isa", std::string());
    r.diagnostics = j.value("diagnostics", true);
    r.cull = j.value("cull", std::string("auto"));
    r.referenceIsa = j.value("reference_isa", std::string());
    r.referenceBuild = j.value("reference_build", std::string());
    r.speedupWithBuildQuality = j.value("speedup_with_build_quality", std::string());
    r.referenceBuildMs = j.at("reference_build_ms").get<double>();
    r.referenceTraceMs = j.at("reference_trace_ms").get<double>();
    r.speedup = j.at("speedup").get<double>();
    r.speedupMin = j.value("speedup_min", 0.0);
    r.speedupMax = j.value("speedup_max", 0.0);
    r.overDefault = j.value("raster_over_default", 0.0);
    r.overDefaultMin = j.value("raster_over_default_min", 0.0);
    r.overDefaultMax = j.value("raster_over_default_max", 0.0);
    r.rasterRuns = j.value("raster_ms_runs", std::vector<double>{});
    r.traceRuns = j.value("reference_trace_ms_runs", std::vector<double>{});
    r.baryMax = j.at("bary_max_error").get<double>();
    r.baryP999 = j.at("bary_p999_error").get<double>();
    r.disagreementFraction = j.at("disagreement_fraction").get<double>();
    r.coverageFraction = j.value("coverage_fraction", -1.0);
    if (j.contains("load")) r.load = readLoad(j["load"], at + "/load");
    // The chart places these on log axes (an error of 0 on a row of its own).
    const auto finite = [&](const char* field, double value, bool positive) {
      if (std::isfinite(value) && (positive ? value > 0 : value >= 0)) return;
      throw badInput(at + "/" + field, "is " + formatNumber(value) + (positive ? "; must be finite and > 0" : "; must be finite and >= 0"));
    };
    finite("raster_ms", r.rasterMs, true);
    finite("bary_p999_error", r.baryP999, false);
    finite("disagreement_fraction", r.disagreementFraction, false);
    if (j.contains("coverage_fraction")) finite("coverage_fraction", r.coverageFraction, false);
    return r;
  });
}

BenchMachine readMachine(const nlohmann::json& j, const std::string& at) {
  return readFields(at, [&] {
    BenchMachine m;
    m.cpu = j.at("cpu").get<std::string>();
    m.logicalCpus = j.at("logical_cpus").get<int>();
    m.widestKernelIsa = j.at("widest_kernel_isa").get<std::string>();
    m.fastestEmbreeIsa = j.at("fastest_embree_isa").get<std::string>();
    m.compiler = j.at("compiler").get<std::string>();
    m.embree = j.at("embree").get<std::string>();
    m.rastercheck = j.at("rastercheck").get<std::string>();
    return m;
  });
}

}  // namespace

BenchResults readBenchJson(const std::string& path) {
  const nlohmann::json doc = readJsonFile(path, "bench results");
  if (!doc.is_object() || doc.value("format_version", 0) != 1 || !doc.contains("rows") || !doc["rows"].is_array()) {
    throw badInput(path, "not a rastercheck bench report (format_version 1 with rows)");
  }
  std::vector<BenchRow> rows;
  for (std::size_t i = 0; i < doc["rows"].size(); ++i) rows.push_back(readRow(doc["rows"][i], path + ": /rows/" + std::to_string(i)));
  if (rows.empty()) throw badInput(path + ": /rows", "no rows");
  BenchResults results{rows, std::nullopt, std::nullopt};
  if (doc.contains("machine")) results.machine = readMachine(doc["machine"], path + ": /machine");
  if (doc.contains("load")) results.load = readLoad(doc["load"], path + ": /load");
  return results;
}

namespace {

// A CSV field in quotes, a quote in it doubled (RFC 4180): a file name may hold either.
std::string csvQuoted(const std::string& field) {
  std::string out = "\"";
  for (char c : field) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

std::string benchCsv(const std::vector<BenchRow>& rows) {
  std::ostringstream out;
  out << "scene,triangles,width,height,threads,setting,default,runs,raster_ms,raster_ms_min,raster_ms_max,"
         "transform_ms,setup_ms,bin_ms,tiles_ms,reference_build_ms,reference_trace_ms,speedup,speedup_with_build,"
         "triangles_per_second,pixels_per_second,bary_max_error,bary_p999_error,disagreement_fraction,exr_write_ms,"
         "reference_isa,raster_isa,store_floor_ms,diagnostics,cull,speedup_min,speedup_max,reference_build,"
         "reference_low_build_ms,reference_low_trace_ms,reference_medium_build_ms,reference_medium_trace_ms,"
         "speedup_with_build_quality,load_other_processes,load_steal,raster_over_default,raster_over_default_min,"
         "raster_over_default_max,coverage_fraction\n";
  char line[768];  // every field after the scene: numbers and short names
  for (const BenchRow& r : rows) {
    char exr[32] = "";  // empty: not measured for this setting
    if (r.exrWriteMs >= 0) std::snprintf(exr, sizeof exr, "%.4g", r.exrWriteMs);
    char load[2][32] = {};  // other processes, steal; empty where not measured
    if (r.load) {
      std::snprintf(load[0], sizeof load[0], "%.4g", r.load->others);
      std::snprintf(load[1], sizeof load[1], "%.4g", r.load->steal);
    }
    char overDefault[3][32] = {};  // the median's ratio, the least and the greatest round's; empty where none
    if (r.overDefault > 0) {
      std::snprintf(overDefault[0], sizeof overDefault[0], "%.4g", r.overDefault);
      std::snprintf(overDefault[1], sizeof overDefault[1], "%.4g", r.overDefaultMin);
      std::snprintf(overDefault[2], sizeof overDefault[2], "%.4g", r.overDefaultMax);
    }
    char builds[2][2][32] = {};  // low, medium: build, trace; empty where not measured
    for (const BenchRow::ReferenceBuild& b : r.referenceBuilds) {
      const int k = b.build == "low" ? 0 : b.build == "medium" ? 1 : -1;
      if (k < 0) continue;
      std::snprintf(builds[k][0], sizeof builds[k][0], "%.4g", b.buildMs);
      std::snprintf(builds[k][1], sizeof builds[k][1], "%.4g", b.traceMs);
    }
    std::snprintf(line, sizeof line,
                  ",%zu,%d,%d,%d,%s,%s,%d,%.4g,%.4g,%.4g,%.4g,%.4g,%.4g,%.4g,%.4g,%.4g,%.4g,%.4g,%.4g,%.4g,%.4g,"
                  "%.4g,%.4g,%s,%s,%s,%.4g,%s,%s,%.4g,%.4g,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%.4g\n",
                  r.triangles, r.width, r.height, r.threads, r.setting.c_str(),
                  r.isDefault ? "true" : "false", r.runs, r.rasterMs, r.rasterMsMin, r.rasterMsMax, r.transformMs,
                  r.setupMs, r.binMs, r.tilesMs, r.referenceBuildMs, r.referenceTraceMs, r.speedup,
                  r.speedupWithBuild, r.trianglesPerSecond, r.pixelsPerSecond, r.baryMax, r.baryP999,
                  r.disagreementFraction, exr, r.referenceIsa.c_str(), r.rasterIsa.c_str(), r.storeFloorMs,
                  r.diagnostics ? "true" : "false", r.cull.c_str(), r.speedupMin, r.speedupMax, r.referenceBuild.c_str(),
                  builds[0][0], builds[0][1], builds[1][0], builds[1][1], r.speedupWithBuildQuality.c_str(), load[0],
                  load[1], overDefault[0], overDefault[1], overDefault[2], r.coverageFraction);
    out << csvQuoted(r.scene) << line;
  }
  return out.str();
}

}  // namespace rc::app

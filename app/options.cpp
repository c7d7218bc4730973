// Shared CLI options.
#include "app/options.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <string_view>

#include "core/error.h"
#include "scenes/scene_loader.h"

namespace rc::app {

namespace {

// A finite number >= 0 in all of `text`, or nothing.
std::optional<double> finiteNonNegative(std::string_view text) {
  double value = 0.0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value) || value < 0.0) return {};
  return value;
}

// CLI11's NonNegativeNumber lets NaN through (NaN < 0 is false); this one does not.
const CLI::Validator kFiniteNonNegative(
    [](std::string& text) -> std::string {
      return finiteNonNegative(text) ? "" : "must be a finite number >= 0, got '" + text + "'";
    },
    "FINITE>=0");

// Why an item of --max-attr or --warn-attr is refused, or "": LIMIT (every attribute) or
// NAME=LIMIT (attribute NAME).
std::string attributeLimitProblem(const std::string& text) {
  const std::size_t equals = text.find('=');
  const std::string_view limit = equals == std::string::npos ? std::string_view(text)
                                                             : std::string_view(text).substr(equals + 1);
  if (equals == 0) return "'" + text + "' names no attribute before '='";
  if (!finiteNonNegative(limit)) return "must be LIMIT or NAME=LIMIT with LIMIT a finite number >= 0, got '" + text + "'";
  return {};
}

// The items of a comma-separated list, empty ones kept: "a,,b" is a, "" and b.
std::vector<std::string> listItems(const std::string& text) {
  std::vector<std::string> items;
  for (std::size_t start = 0;;) {
    const std::size_t comma = text.find(',', start);
    items.push_back(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) return items;
    start = comma + 1;
  }
}

// --max-attr's or --warn-attr's items, each already checked: a bare limit sets every
// attribute's (`every`, a double or an optional one), NAME=LIMIT one attribute's. Naming an
// attribute twice, or giving two bare limits, is refused: which was meant?
template <typename Every>
void setAttributeLimits(const char* option, const std::vector<std::string>& items, Every& every,
                        std::map<std::string, double>& byName) {
  bool bare = false;
  for (const std::string& item : items) {
    const std::size_t equals = item.find('=');
    if (equals == std::string::npos) {
      if (bare) throw CLI::ValidationError(option, "two limits for every attribute; give one");
      bare = true;
      every = *finiteNonNegative(item);
      continue;
    }
    const std::string name = item.substr(0, equals);
    if (!byName.emplace(name, *finiteNonNegative(std::string_view(item).substr(equals + 1))).second) {
      throw CLI::ValidationError(option, "attribute " + name + " given two limits; give one");
    }
  }
}

// --max-attr or --warn-attr: LIMIT or NAME=LIMIT, comma-separated or repeated.
template <typename Every>
void addAttributeLimitOption(CLI::App* command, const char* option, Every& every, std::map<std::string, double>& byName,
                             const std::string& help) {
  addListOption(
      command, option,
      [option, &every, &byName](const std::vector<std::string>& items) { setAttributeLimits(option, items, every, byName); },
      help, attributeLimitProblem)
      ->type_name("LIMIT|NAME=LIMIT[,...]");
}

}  // namespace

CLI::Option* addListOption(CLI::App* command, const std::string& name, std::function<void(std::vector<std::string>)> take,
                           const std::string& help, std::function<std::string(const std::string&)> checkItem) {
  return command
      ->add_option_function<std::vector<std::string>>(
          name,
          [take](const std::vector<std::string>& given) {
            std::vector<std::string> items;
            for (const std::string& text : given) {
              for (std::string& item : listItems(text)) items.push_back(std::move(item));
            }
            take(std::move(items));
          },
          help)
      ->allow_extra_args(false)
      ->check(CLI::Validator(
          [checkItem](std::string& text) -> std::string {
            for (const std::string& item : listItems(text)) {
              if (item.empty()) return "'" + text + "' has an empty item; separate the items with single commas (a,b)";
              if (checkItem) {
                if (std::string problem = checkItem(item); !problem.empty()) return problem;
              }
            }
            return {};
          },
          ""));
}

void refuseEmptyAssignments(int argc, const char* const* argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "--") return;
    if (arg.size() > 3 && arg.substr(0, 2) == "--" && arg.find('=') == arg.size() - 1) {
      const std::string name(arg.substr(0, arg.size() - 1));
      throw CLI::ValidationError(std::string(arg), "nothing follows '='; give the value (" + name +
                                                       "=VALUE or " + name + " VALUE) or leave the option out");
    }
  }
}

std::string lowerCase(std::string text) {
  for (char& ch : text) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  return text;
}

void addRenderOptions(CLI::App* command, RenderSettings& s) {
  addChoice<Interpolation>(command, "--mode", s.raster.interpolation,
                           {{"perspective", Interpolation::kPerspective}, {"affine", Interpolation::kAffine}},
                           "rasterizer interpolation");
  addChoice<Precision>(command, "--precision", s.raster.precision,
                       {{"float", Precision::kFloat}, {"double", Precision::kDouble}}, "rasterizer arithmetic");
  addChoice<DepthMapping>(command, "--depth-mapping", s.raster.depthMapping,
                          {{"inverse-w", DepthMapping::kInverseW}, {"standard", DepthMapping::kStandard}},
                          "rasterizer depth-test key: 1/w, or the standard d = 1 - n/w (docs/rasterizer.md)");
  addChoice<Culling>(command, "--cull", s.raster.culling, {{"auto", Culling::kAuto}, {"none", Culling::kNone}},
                     "rasterizer back faces: auto culls them where they cannot be seen (a closed solid "
                     "wholly beyond the near plane, docs/rasterizer.md), none draws them");
  addChoice<FillRule>(command, "--fill-rule", s.raster.fillRule,
                      {{"top-left", FillRule::kTopLeft}, {"inclusive", FillRule::kInclusive},
                       {"exclusive", FillRule::kExclusive}},
                      "rasterizer: which pixel centres on an edge a triangle covers; only top-left is right, the others "
                      "are wrong on purpose, to see the gate fail them");
  command->add_option("--subpixel-bits", s.raster.subpixelBits,
                      "fraction bits of snapped vertex positions used for coverage (1..16), or none: coverage of "
                      "the unsnapped triangle, decided exactly")
      ->transform(CLI::Validator(
          [](std::string& value) -> std::string {
            if (lowerCase(value) == "none") {
              value = "0";
              return "";
            }
            const bool digits = !value.empty() && value.size() <= 2 &&
                                std::all_of(value.begin(), value.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
            if (digits && std::stoi(value) >= 1 && std::stoi(value) <= 16) return "";
            return "must be 1..16 or none, got " + value;
          },
          ""))
      ->type_name("1..16|none")
      ->default_str("8");
  addChoice<KernelIsa>(command, "--raster-isa", s.raster.isa,
                       {{"auto", KernelIsa::kAuto}, {"sse2", KernelIsa::kSse2}, {"avx2", KernelIsa::kAvx2},
                        {"avx512", KernelIsa::kAvx512}},
                       "instruction set of the rasterizer's pixel kernels; every choice gives the same bits");
  command->add_flag_function(
      "--no-diagnostics", [&s](std::int64_t given) { s.raster.diagnostics = given <= 0; },  // =false counts -1
      "rasterizer: leave out bound.bary, bound.depth, edge.dist and depth.tie (compare then falls back to fixed "
      "thresholds)");
  addThreadsOption(command, s.threads, "worker threads");
  addChoice<std::string>(command, "--embree-isa", s.reference.isa,
                         {{"sse2", "sse2"}, {"sse4.2", "sse4.2"}, {"avx", "avx"}, {"avx2", "avx2"}, {"avx512", "avx512"}},
                         "Embree instruction set, pinned so results do not change with the CPU");
  addChoice<EmbreeBuild>(command, "--embree-build", s.reference.build,
                         {{"low", EmbreeBuild::kLow}, {"medium", EmbreeBuild::kMedium}, {"high", EmbreeBuild::kHigh}},
                         "quality of Embree's BVH build: low builds fastest (one frame), medium and high trace a "
                         "little faster; only which triangle wins a tie on an edge can move with it");
  addSceneOptions(command, s);
}

void addSceneOptions(CLI::App* command, RenderSettings& s) {
  command->add_option("--size", s.size, "image size WxH, overriding the scene's (e.g. 1920x1080)");
  command->add_option("--eye", s.eye, "camera position x,y,z, overriding the scene's");
  command->add_option("--target", s.target, "point the camera looks at, x,y,z");
  command->add_option("--up", s.up, "camera up direction x,y,z, overriding the scene's (needed where the view is along it)");
  command->add_option("--fov", s.fovYDegrees, "vertical field of view in degrees")->check(CLI::Range(kMinFovYDegrees, kMaxFovYDegrees));
  command->add_option("--camera", s.camera,
                      "glTF files: the camera to render through, by its index in the file's cameras or its name "
                      "(default: the first the scene places)")
      ->type_name("INDEX|NAME");
  addListOption(
      command, "--attributes", [&s](std::vector<std::string> names) { s.attributes = std::move(names); },
      "attributes to interpolate and write (e.g. uv,normal); default: all the scene carries")
      ->type_name("NAME[,NAME]");
  command->add_option("--max-triangles", s.maxTriangles, "refuse scenes with more triangles than this")
      ->check(CLI::Range(1LL, 4'000'000'000LL))->capture_default_str();
  command->add_option("--max-image-side", s.maxImageSide, "refuse images wider or taller than this")
      ->check(CLI::Range(1, 16384))->capture_default_str();
}

void addThresholdOptions(CLI::App* command, Thresholds& t) {
  addChoice<HeatmapQuantity>(command, "--heatmap-shows", t.heatmap,
                             {{"error", HeatmapQuantity::kError}, {"ulps", HeatmapQuantity::kUlps},
                              {"bound", HeatmapQuantity::kBoundRatio}},
                             "what the heatmap colours show: error, ulps, or bound (error / bound)");
  // Without the diagnostics channels (images from elsewhere), these fixed limits gate instead.
  command->add_option("--max-bary", t.bary, "gate without bound channels: max barycentric error (absolute)")
      ->check(kFiniteNonNegative)->capture_default_str();
  command->add_option("--max-depth", t.depth, "gate without bound channels: max depth error (relative)")
      ->check(kFiniteNonNegative)->capture_default_str();
  addAttributeLimitOption(command, "--max-attr", t.attribute, t.attributeByName,
                          "gate without bound channels: max attribute error, as a fraction of its range; LIMIT for "
                          "every attribute, NAME=LIMIT for one (e.g. 1e-4,color=4e-3); default 0.0001");
  command->add_option("--max-disagreement", t.disagreement,
                      "gate without edge.dist channels: max fraction of covered pixels where the triangle differs, "
                      "depth ties left out")
      ->check(kFiniteNonNegative)->capture_default_str();
  command->add_option("--max-coverage", t.coverage,
                      "gate without edge.dist channels: max fraction of covered pixels covered by one image only, "
                      "clip ties left out")
      ->check(kFiniteNonNegative)->capture_default_str();
  // Warning limits: the same values in the same units, whatever gates them; never fail.
  const std::string warns = "warn (exit 0 unless --fail-on-warnings) when ";
  command->add_option("--warn-bary", t.warn.bary, warns + "the max barycentric error (absolute) exceeds this")
      ->check(kFiniteNonNegative);
  command->add_option("--warn-depth", t.warn.depth, warns + "the max depth error (relative) exceeds this")
      ->check(kFiniteNonNegative);
  addAttributeLimitOption(command, "--warn-attr", t.warn.attribute, t.warn.attributeByName,
                          warns + "an attribute's max error, as a fraction of its range, exceeds this; LIMIT for "
                                  "every attribute, NAME=LIMIT for one");
  command->add_option("--warn-disagreement", t.warn.disagreement,
                      warns + "the fraction of covered pixels where the triangle differs exceeds this")
      ->check(kFiniteNonNegative);
  command->add_option("--warn-coverage", t.warn.coverage,
                      warns + "the fraction of covered pixels covered by one image only exceeds this")
      ->check(kFiniteNonNegative);
  command->add_flag("--fail-on-warnings", t.warn.fail,
                    "every warning (--warn-*, --baseline) fails the gate (exit 1) as one of its reasons");
  command->add_flag("--allow-empty", t.allowEmpty,
                    "let a pair of images in which neither covers a pixel pass (by default it fails: nothing was compared)");
}

void addBaselineOptions(CLI::App* command, BaselineUse& baseline, const std::string& writtenBy) {
  CLI::Option* file = command->add_option(
      "--baseline", baseline.file,
      "hold the figures to an earlier report (" + writtenBy +
          "): warn (exit 0 unless --fail-on-warnings) for each error or disagreement fraction that grew by more "
                          "than --baseline-factor")
      ->type_name("FILE");
  command
      ->add_option("--baseline-factor", baseline.factor,
                   "with --baseline: how many times its figure a figure may reach before it is a warning (>= 1)")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            const std::optional<double> factor = finiteNonNegative(text);
            return factor && *factor >= 1.0 ? "" : "must be a finite number >= 1, got '" + text + "'";
          },
          ""))
      ->type_name("F")
      ->needs(file)
      ->capture_default_str();
}

void noteIdleFailOnWarnings(const Thresholds& t, const BaselineUse& baseline) {
  const Thresholds::Warnings& w = t.warn;
  const bool anyLimit = w.bary || w.depth || w.attribute || w.disagreement || w.coverage || !w.attributeByName.empty();
  if (w.fail && !anyLimit && baseline.file.empty()) {
    std::fprintf(stderr, "rastercheck: note: --fail-on-warnings has nothing to fail on: no --warn-* limit or --baseline "
                         "was given\n");
  }
}

std::vector<std::string> givenLimits(const CLI::App& command) {
  std::vector<std::string> given;
  for (const char* name : {"--max-bary", "--max-depth", "--max-attr", "--max-disagreement", "--max-coverage"}) {
    if (command.count(name) > 0) given.emplace_back(name);
  }
  return given;
}

void noteUnappliedLimits(const std::vector<std::string>& given, const std::vector<const CompareReport*>& reports) {
  // Whether `limit` gated something in report r.
  const auto applied = [](const std::string& limit, const CompareReport& r) {
    if (limit == "--max-disagreement" || limit == "--max-coverage") return !r.explained;
    for (const FamilyReport& f : r.families) {
      const bool mine = limit == "--max-bary" ? f.name == "bary" : limit == "--max-depth" ? f.name == "depth" : f.isAttribute();
      if (mine && !f.bounded) return true;
    }
    return false;
  };
  const bool anyAttribute = std::any_of(reports.begin(), reports.end(), [](const CompareReport* r) {
    return std::any_of(r->families.begin(), r->families.end(), [](const FamilyReport& f) { return f.isAttribute(); });
  });
  std::string bounded, noAttribute;
  for (const std::string& limit : given) {
    if (std::any_of(reports.begin(), reports.end(), [&](const CompareReport* r) { return applied(limit, *r); })) continue;
    std::string& list = limit == "--max-attr" && !anyAttribute ? noAttribute : bounded;
    list += (list.empty() ? "" : ", ") + limit;
  }
  if (!bounded.empty()) {
    std::fprintf(stderr,
                 "rastercheck: note: %s gated nothing: both images carry the bound channels, so each pixel is gated "
                 "against its own bound and each disagreement must be explained (docs/compare.md)\n",
                 bounded.c_str());
  }
  if (!noAttribute.empty()) {
    std::fprintf(stderr, "rastercheck: note: --max-attr gated nothing: no attribute was compared\n");
  }
}

void addExrCompressionOption(CLI::App* command, ExrCompression& compression) {
  addChoice<ExrCompression>(command, "--exr-compression", compression,
                            {{"zip", ExrCompression::kZip}, {"piz", ExrCompression::kPiz},
                             {"zips", ExrCompression::kZips}, {"rle", ExrCompression::kRle},
                             {"none", ExrCompression::kNone}},
                            "lossless codec of the EXR files written: zip, piz (faster and smaller for full frames of "
                            "tiny triangles), zips, rle, or none (fastest, largest)");
}

void addThreadsOption(CLI::App* command, int& threads, const std::string& what) {
  command->add_option("--threads", threads, what + ", 0 = all cores")->check(CLI::Range(0, 256))->capture_default_str();
}

void finishRenderSettings(RenderSettings& s) {
  s.raster.threads = s.threads;
  s.reference.threads = s.threads;
}

namespace {

glm::dvec3 parseVec3(const std::string& text, const char* option) {
  glm::dvec3 v;
  const char* p = text.data();
  const char* end = text.data() + text.size();
  for (int i = 0; i < 3; ++i) {
    auto [next, ec] = std::from_chars(p, end, v[i]);
    const bool separatorOk = i < 2 ? (next < end && *next == ',') : next == end;
    if (ec != std::errc() || !separatorOk || !std::isfinite(v[i])) {
      throw usageError(std::string(option) + " must be three finite numbers x,y,z, got '" + text + "'");
    }
    p = next + 1;
  }
  return v;
}

}  // namespace

Scene loadScene(const std::string& spec, const RenderSettings& settings) {
  SceneOverrides o;
  if (!settings.size.empty()) {
    const std::string& text = settings.size;
    const std::size_t x = text.find('x');
    const bool ok = x != std::string::npos &&
                    std::from_chars(text.data(), text.data() + x, o.width).ptr == text.data() + x &&
                    std::from_chars(text.data() + x + 1, text.data() + text.size(), o.height).ptr ==
                        text.data() + text.size();
    if (!ok || o.width < 1 || o.height < 1 || o.width > 16384 || o.height > 16384) {
      throw usageError("--size must be WxH with 1..16384 per side, got '" + text + "'");
    }
  }
  if (!settings.eye.empty()) o.eye = parseVec3(settings.eye, "--eye");
  if (!settings.target.empty()) o.target = parseVec3(settings.target, "--target");
  if (!settings.up.empty()) o.up = parseVec3(settings.up, "--up");
  if (settings.fovYDegrees > 0) o.fovYDegrees = settings.fovYDegrees;
  if (!settings.attributes.empty()) o.attributes = settings.attributes;
  o.camera = settings.camera;
  o.maxTriangles = std::size_t(settings.maxTriangles);
  Scene scene = rc::loadScene(spec, o);
  if (std::size_t(settings.maxTriangles) < scene.mesh.triangleCount()) {
    throw badInput(spec, std::to_string(scene.mesh.triangleCount()) + " triangles exceed --max-triangles " +
                             std::to_string(settings.maxTriangles));
  }
  if (std::max(scene.camera.width(), scene.camera.height()) > settings.maxImageSide) {
    throw badInput(spec, "image " + std::to_string(scene.camera.width()) + "x" + std::to_string(scene.camera.height()) +
                             " exceeds --max-image-side " + std::to_string(settings.maxImageSide));
  }
  return scene;
}

}  // namespace rc::app

// shadesim render's engine (its options: sim/cli/render.cpp): shade a scene through the
// bit-accurate model, beside the float reference, and report the error with the cost.
#include "sim/engines/render.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

#include "derive/accuracy_checks.h"
#include "host/frame.h"
#include "host/image.h"
#include "host/metrics.h"
#include "host/prepared_scene.h"
#include "host/reference.h"
#include "model/shade_unit.h"
#include "model/specular_units.h"
#include "model/text_file.h"
#include "sim/engines/unit_choice.h"

namespace shadesim {
namespace {

Image model_image(const std::vector<PixelOut>& pixels, int width, int height, int channels,
                  int out_bits) {
  Image img(width, height, channels);
  const int shift = out_bits > 8 ? out_bits - 8 : 0;
  for (const auto& p : pixels) {
    for (int c = 0; c < channels; ++c) {
      img.pixels[(static_cast<size_t>(p.y) * static_cast<size_t>(width) + p.x) *
                     static_cast<size_t>(channels) +
                 static_cast<size_t>(c)] =
          static_cast<uint8_t>(p.colour[static_cast<size_t>(c)] >> shift);
    }
  }
  return img;
}

// PSNR in dB; an image with no pixel has none (the error stats of no samples are 0, not a PSNR).
std::string format_db(double db, size_t pixels) {
  if (pixels == 0) return "n/a (no pixels)";
  if (std::isinf(db)) return "inf (identical)";
  std::ostringstream os;
  os << std::fixed << std::setprecision(2) << db << " dB";
  return os.str();
}

// The two error lines of render's summary; an image with no pixel says so (no error, no PSNR).
std::string error_lines(const ErrorStats& es) {
  std::ostringstream os;
  if (es.pixels == 0) {
    os << "error        none: the image is empty (no pixel covered), so there is no error or "
          "PSNR to report\n"
       << "warning      empty image: check the camera, the objects and the culled counts above\n";
    return os.str();
  }
  os << "error        max " << es.max_code_lsb << " LSB (8-bit codes vs rounded reference), mean "
     << std::setprecision(4) << es.mean_code_lsb << " LSB, PSNR "
     << format_db(es.psnr_db, es.pixels) << "\n"
     << "             max " << std::setprecision(3) << es.max_real_lsb
     << " LSB before rounding the reference; " << es.pixels_over_1lsb
     << " pixel(s) off by more than 1\n";
  return os.str();
}

// "blinn (N.H)", "phong (R.V)", or per material when they differ.
std::string specular_models(const Scene& scene) {
  auto describe = [](SpecularModel m) {
    return std::string(to_string(m)) + (m == SpecularModel::kPhong ? " (R.V)" : " (N.H)");
  };
  const SpecularModel first = scene.materials.front().specular_model;
  const bool same = std::all_of(scene.materials.begin(), scene.materials.end(),
                                [&](const Material& m) { return m.specular_model == first; });
  if (same) return describe(first);
  std::string text;
  for (const Material& m : scene.materials) {
    text += (text.empty() ? "" : ", ") + m.name + ": " + describe(m.specular_model);
  }
  return text;
}

// The frame options and output directory both render modes share. `note`, when given, gets
// what the unit line says of --config (unit_choice_note: whether own was derived or reused).
FrameOptions frame_options(const RenderOptions& o, std::string* note = nullptr) {
  FrameOptions fo;
  const std::string said = use_unit_choice(o.config, o.scene, o.widths, fo);
  if (note) *note = said;
  if (!std::isnan(o.budget_lsb)) fo.budget_lsb = o.budget_lsb;
  fo.max_depth = o.max_depth;
  if (!o.specular.empty()) fo.specular_override = parse_specular_unit(o.specular, "--specular");
  return fo;
}

std::filesystem::path output_dir(const RenderOptions& o) {
  std::filesystem::path dir =  // returned: moved
      o.out_dir.empty() ? std::filesystem::path("out") / std::filesystem::path(o.scene).stem()
                        : std::filesystem::path(o.out_dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// PSNR for JSON: null where the summary prints no number (identical images, no pixels).
nlohmann::json psnr_json(const ErrorStats& e) {
  return std::isinf(e.psnr_db) || e.pixels == 0 ? nlohmann::json(nullptr)
                                                : nlohmann::json(e.psnr_db);
}

// The images one render writes.
struct RenderImages {
  std::string model, reference, error, compare;
};

RenderImages render_images(const std::filesystem::path& dir) {
  return {(dir / "model.png").string(), (dir / "reference.png").string(),
          (dir / "error.png").string(), (dir / "compare.png").string()};
}

// One render: the frame, the model's pixels against the reference, the images written. The
// summary and --json both report from here, so each figure is computed once.
struct RenderRun {
  FrameOptions fo;
  // Prepared once: the accuracy checks re-shade the same frame on variants of the unit.
  std::unique_ptr<PreparedScene> prepared;
  UnitConfig unit;
  EncodedFrame encoded;
  FrameTimings timings;
  ErrorMap err;
  double model_s = 0, reference_s = 0;
  RenderImages images;
  std::string unit_label;
  std::string unit_note;  // "--config own: cached derivation, PATH"
  std::vector<std::string> warnings;

  const Scene& scene() const { return prepared->scene(); }
  const UnitConfig& config() const { return unit; }
  const ProjectStats& projected() const { return prepared->project(); }
  const SetupStats& setup() const { return prepared->setup().stats; }
  const EncodeStats& stream() const { return encoded.stats; }
  const ErrorStats& error() const { return err.stats; }
  double model_mpixel_per_s() const { return model_s > 0 ? error().pixels / model_s / 1e6 : 0.0; }
};

// The model's pixels against the reference, and the images: the pixels and images go before the
// accuracy checks re-shade the frame (a 1080p frame's peak memory).
void shade_and_write(const RenderOptions& o, const PreparedScene& frame, RenderRun& r) {
  const Scene& scene = frame.scene();
  const UnitConfig& cfg = r.unit;
  ShadeUnit unit(cfg);
  std::vector<PixelOut> pixels;
  pixels.reserve(r.encoded.stats.pixels);
  const auto t0 = std::chrono::steady_clock::now();
  for (const auto& cmd : r.encoded.stream.commands) {
    unit.consume(cmd, [&pixels](const PixelOut& p) { pixels.push_back(p); });
  }
  r.model_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  const auto t1 = std::chrono::steady_clock::now();
  const ReferenceImage& ref = frame.reference(cfg.channels);
  r.reference_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();

  r.err = compare_to_reference(pixels, ref.values, frame.visibility().owner, scene.width,
                               scene.height, cfg.channels, cfg.out_bits);

  // Images: model, reference, error heat map, and the three side by side.
  r.images = render_images(output_dir(o));
  const Image model_png =
      model_image(pixels, scene.width, scene.height, cfg.channels, cfg.out_bits);
  Image ref_png(scene.width, scene.height, cfg.channels);
  ref_png.pixels = reference_codes(ref.values, cfg.out_bits);
  const Image heat =
      error_heat_map(r.err.per_pixel_lsb, scene.width, scene.height, o.heat_scale_lsb);
  write_png(r.images.model, model_png);
  write_png(r.images.reference, ref_png);
  write_png(r.images.error, heat);
  write_png(r.images.compare, hstack({model_png, ref_png, heat}, 4));
  if (!o.stream_path.empty()) r.encoded.stream.save(o.stream_path);
}

RenderRun shade_and_compare(const RenderOptions& o) {
  RenderRun r;
  r.fo = frame_options(o, &r.unit_note);
  const FrameOptions& fo = r.fo;
  r.prepared = std::make_unique<PreparedScene>(
      o.scene, PrepareKey{fo.budget_lsb, fo.max_depth, fo.base.out_bits});
  const PreparedScene& frame = *r.prepared;
  const Scene& scene = frame.scene();
  r.unit = frame_unit_on(scene, o.scene, fo, o.config);
  const UnitConfig& cfg = r.unit;
  r.timings = frame.timings();
  const auto te = std::chrono::steady_clock::now();
  r.encoded = encode_frame(scene, cfg, frame.setup(), frame.visibility());
  r.timings.encode_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - te).count();

  shade_and_write(o, frame, r);
  r.unit_label = cfg.specular.describe() + (cfg.specular.kind == SpecularUnitKind::kIdeal
                                                ? " (exact pow of the fixed-point t; not hardware)"
                                            : cfg.specular.kind == SpecularUnitKind::kNone
                                                ? " (no specular term: highlights not shaded)"
                                                : "");
  r.warnings = accuracy_warnings(frame, cfg, r.encoded.stream, r.err.stats);
  return r;
}

// The figures, as lines.
void print_render(const RenderOptions& o, const RenderRun& r) {
  const Scene& scene = r.scene();
  const UnitConfig& cfg = r.config();
  const ProjectStats& pr = r.projected();
  const SetupStats& st = r.setup();
  const EncodeStats& stream = r.stream();
  const ErrorStats& es = r.error();
  const FrameTimings& timings = r.timings;
  std::cout << "scene        " << o.scene << "  (" << scene.width << "x" << scene.height << ", "
            << scene.lights.size() << " light(s), eye "
            << (scene.eye_at_infinity ? "at infinity" : "finite") << ")\n"
            << "unit         " << cfg.to_string() << "  (" << r.unit_note << ")\n"
            << "specular     " << r.unit_label << "\n"
            << "triangles    " << pr.triangles_in << " in mesh, " << pr.emitted
            << " after culling; " << st.triangles_out << " after setup (" << st.inputs_split
            << " split, " << st.splits << " splits, " << st.over_budget << " over budget at depth "
            << r.fo.max_depth << ")\n"
            << "culled       " << pr.culled_back_face << " back-facing, " << pr.culled_near
            << " wholly nearer than the near plane, " << pr.dropped_out_of_range
            << " beyond the screen coordinate range\n"
            << "clipped      " << pr.clipped_near << " crossing the near plane, clipped into "
            << pr.clipped_pieces << " triangle(s) before culling\n"
            << "cosine       " << specular_models(scene) << "\n"
            << "stream       " << stream.triangles << " tri, " << stream.spans << " spans, "
            << stream.materials << " material loads, " << stream.words << " words; "
            << stream.reorigins << " re-origin(s) (offset_bits " << cfg.offset_bits << ")\n"
            << "pixels       " << es.pixels << " shaded\n"
            << error_lines(es) << "setup budget "
            << (r.fo.budget_lsb ? *r.fo.budget_lsb : scene.error_budget_lsb)
            << " LSB Taylor error per triangle; worst measured " << std::setprecision(3)
            << st.worst_error_lsb << " LSB\n"
            << "time         setup " << std::setprecision(3) << timings.setup_s << " s, visibility "
            << timings.visibility_s << " s, model " << r.model_s << " s (" << std::setprecision(3)
            << r.model_mpixel_per_s() << " Mpixel/s), reference " << r.reference_s << " s\n"
            << "images       " << r.images.compare << " (model | reference | error, full scale "
            << o.heat_scale_lsb << " LSB)\n";
  for (const auto& w : r.warnings) std::cout << "warning      " << w << "\n";
  if (stream.narrow_terms_saturated > 0) {
    std::cout << "warning      " << stream.narrow_terms_saturated
              << " Taylor coefficient(s) saturated their term's narrowed format (coef_term_iwl);"
                 " pixels of those triangles are wrong: give those terms more integer bits\n";
  }
  if (stream.coefficients_out_of_range > 0) {
    if (cfg.coef.overflow == Overflow::kSaturate) {
      std::cout << "warning      " << stream.coefficients_out_of_range
                << " Taylor coefficient(s) saturated the coef format " << cfg.coef.to_string()
                << "; pixels of those triangles are wrong: widen --coef or let it :wrap\n";
    } else {
      std::cout << "note         " << stream.coefficients_out_of_range
                << " Taylor coefficient(s) wrapped in " << cfg.coef.to_string()
                << " (exact modulo 2^" << cfg.coef.iwl << "; sliver triangles)\n";
    }
  }
}

// The figures, as --json.
void write_render_json(const RenderOptions& o, const RenderRun& r) {
  const ProjectStats& pr = r.projected();
  const SetupStats& st = r.setup();
  const EncodeStats& stream = r.stream();
  const ErrorStats& es = r.error();
  const FrameTimings& timings = r.timings;
  nlohmann::json j;
  j["scene"] = o.scene;
  j["width"] = r.scene().width;
  j["height"] = r.scene().height;
  j["config"] = nlohmann::json::parse(config_to_json(r.config()));
  j["unit_choice"] = o.config;
  j["warnings"] = r.warnings;
  j["specular_unit"] = r.unit_label;
  j["triangles"] = {{"mesh", pr.triangles_in},
                    {"projected", pr.emitted},
                    {"after_setup", st.triangles_out},
                    {"inputs_split", st.inputs_split},
                    {"splits", st.splits},
                    {"over_budget", st.over_budget},
                    {"worst_setup_error_lsb", st.worst_error_lsb},
                    {"culled_back_face", pr.culled_back_face},
                    {"culled_near", pr.culled_near},
                    {"dropped_out_of_range", pr.dropped_out_of_range},
                    {"clipped_near", pr.clipped_near},
                    {"clipped_pieces", pr.clipped_pieces}};
  nlohmann::json models = nlohmann::json::object();
  for (const Material& m : r.scene().materials) models[m.name] = to_string(m.specular_model);
  j["specular_model"] = models;
  j["stream"] = {{"triangles", stream.triangles},
                 {"reorigins", stream.reorigins},
                 {"spans", stream.spans},
                 {"materials", stream.materials},
                 {"words", stream.words},
                 {"coefficients_out_of_range", stream.coefficients_out_of_range}};
  j["pixels"] = es.pixels;
  j["empty_image"] = es.pixels == 0;
  j["error"] = {{"max_code_lsb", es.max_code_lsb},
                {"mean_code_lsb", es.mean_code_lsb},
                {"psnr_db", psnr_json(es)},
                {"max_real_lsb", es.max_real_lsb},
                {"pixels_over_1lsb", es.pixels_over_1lsb},
                {"metric",
                 "output codes vs reference rounded by the same rule; real: before rounding the "
                 "reference"}};
  j["time_s"] = {{"load", timings.load_s},     {"project", timings.project_s},
                 {"setup", timings.setup_s},   {"visibility", timings.visibility_s},
                 {"encode", timings.encode_s}, {"model", r.model_s},
                 {"reference", r.reference_s}};
  j["model_mpixel_per_s"] = r.model_mpixel_per_s();
  j["images"] = {{"model", r.images.model},
                 {"reference", r.images.reference},
                 {"error", r.images.error},
                 {"compare", r.images.compare}};
  j["heat_scale_lsb"] = o.heat_scale_lsb;  // the error map's full scale (red), for its legend
  write_text_file(o.json_path, j.dump(2) + '\n');
}

}  // namespace

int run_render(const RenderOptions& o) {
  const RenderRun r = shade_and_compare(o);
  if (!o.quiet) print_render(o, r);
  if (!o.json_path.empty()) write_render_json(o, r);
  return 0;
}

// Every specular unit on the same scene: the highlights side by side with the reference, and
// one line of error per unit, so a designer can look before reading.
int run_all_units(const RenderOptions& o) {
  FrameOptions fo = frame_options(o);  // --all-units excludes --specular
  const std::filesystem::path out_dir = output_dir(o);

  std::vector<Image> images, heats;
  nlohmann::json units = nlohmann::json::array();
  if (!o.quiet) {
    std::cout << std::left << std::setw(9) << "unit" << std::setw(9) << "max LSB" << std::setw(11)
              << "mean LSB" << std::setw(18) << "PSNR"
              << "configuration\n";
  }
  for (const SpecularUnitDescriptor& unit : specular_units()) {  // model/specular_units.h
    if (unit.series_per_light == 0) continue;                    // none: no highlight to compare
    const SpecularUnitKind kind = unit.kind;
    fo.specular_override = kind;
    const PreparedFrame frame = prepare_frame(o.scene, fo);
    const auto pixels = ShadeUnit(frame.config).run(frame.encoded.stream);
    const ReferenceImage ref = render_reference(frame.setup.triangles, frame.visibility,
                                                frame.scene, frame.config.channels);
    const ErrorMap err =
        compare_to_reference(pixels, ref.values, frame.visibility.owner, frame.scene.width,
                             frame.scene.height, frame.config.channels, frame.config.out_bits);
    if (images.empty()) {
      Image ref_png(frame.scene.width, frame.scene.height, frame.config.channels);
      ref_png.pixels = reference_codes(ref.values, frame.config.out_bits);
      images.push_back(ref_png);
    }
    images.push_back(model_image(pixels, frame.scene.width, frame.scene.height,
                                 frame.config.channels, frame.config.out_bits));
    heats.push_back(
        error_heat_map(err.per_pixel_lsb, frame.scene.width, frame.scene.height, o.heat_scale_lsb));
    const auto& e = err.stats;
    const std::string description = frame.config.specular.describe();
    if (!o.quiet) {
      std::cout << std::left << std::setw(9) << to_string(kind) << std::setw(9) << e.max_code_lsb
                << std::setw(11) << std::setprecision(4) << e.mean_code_lsb << std::setw(18)
                << format_db(e.psnr_db, e.pixels) << description
                << (unit.hardware ? "" : " (exact pow; not hardware)") << "\n";
    }
    units.push_back({{"unit", to_string(kind)},
                     {"configuration", description},
                     {"max_code_lsb", e.max_code_lsb},
                     {"mean_code_lsb", e.mean_code_lsb},
                     {"psnr_db", psnr_json(e)},
                     {"max_real_lsb", e.max_real_lsb},
                     {"table_load_cycles", frame.encoded.stats.table_load_cycles},
                     {"stream_words", frame.encoded.stats.words}});
  }
  write_png((out_dir / "units.png").string(), hstack(images, 4));
  write_png((out_dir / "units_error.png").string(), hstack(heats, 4));
  if (!o.quiet) {
    std::cout << "images   " << (out_dir / "units.png").string()
              << " (reference | ideal | lut | schlick | wpow)\n"
              << "         " << (out_dir / "units_error.png").string()
              << " (error heat maps, same order without the reference; full scale "
              << o.heat_scale_lsb << " LSB)\n";
  }
  if (!o.json_path.empty()) {
    write_text_file(o.json_path,
                    nlohmann::json{{"scene", o.scene}, {"units", units}}.dump(2) + '\n');
  }
  return 0;
}

}  // namespace shadesim

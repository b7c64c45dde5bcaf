// Browser bindings of the lens engine (geolens_lens) with embind: a session per image, updated
// with the lenses of each frame, its warp handed to JS as views into the wasm heap, and its
// points mapped through geolens::WarpMap. The JS face (Session, session(), dispose(), the views)
// is in post.js; this file is its core, SessionCore.
//
// Errors: every entry point catches what the library throws and returns a JS Error with the
// exception's what() (the library's message), which post.js throws, so JS sees an Error with
// the library's message rather than the number emscripten throws for an uncaught C++ exception.

#include <emscripten/bind.h>
#include <emscripten/val.h>
#include <malloc.h>

#include <cmath>
#include <cstdint>
#include <exception>
#include <optional>
#include <string>
#include <vector>

#include "geolens/core/errors.h"
#include "geolens/geometry/roi.h"
#include "geolens/lens/geometric_lens.h"
#include "geolens/lens/lens.h"
#include "geolens/lens/lens_options.h"
#include "geolens/lens/lens_session.h"
#include "geolens/warp/warp_map.h"
#include "geolens/warp/warp_mesh.h"

using emscripten::val;

namespace {

// Runs f (which returns a val) and returns, instead of letting a C++ exception out, a JS Error
// (not thrown: returned, so every C++ destructor has run and nothing leaks) whose message is the
// exception's what() and whose name is the library's exception type (InvalidInput,
// InvalidOption, SolverError, Cancelled, else Error). post.js throws it.
template <class F>
val guarded(F&& f) {
  const char* name = "Error";
  std::string message;
  try {
    return f();
  } catch (const geolens::InvalidOption& e) {
    name = "InvalidOption", message = e.what();
  } catch (const geolens::InvalidInput& e) {
    name = "InvalidInput", message = e.what();
  } catch (const geolens::SolverError& e) {
    name = "SolverError", message = e.what();
  } catch (const geolens::Cancelled& e) {
    name = "Cancelled", message = e.what();
  } catch (const std::bad_alloc&) {
    name = "RangeError", message = "geolens: out of memory";
  } catch (const std::exception& e) {
    message = e.what();
  }
  val error = val::global("Error").new_(message);
  error.set("name", std::string(name));
  return error;
}

bool is_number(const val& v) { return v.typeOf().as<std::string>() == "number"; }

// The numbers of a JS array or typed array; InvalidInput naming `what` for anything else (which
// convertJSArrayToNumberVector would turn into a JS TypeError thrown through the wasm frames).
std::vector<double> numbers_from(const val& v, const std::string& what) {
  if (!val::global("Array").call<bool>("isArray", v) &&
      !val::global("ArrayBuffer").call<bool>("isView", v))
    throw geolens::InvalidInput(what + " must be an array or a typed array of numbers, got " +
                                v.typeOf().as<std::string>());
  return emscripten::convertJSArrayToNumberVector<double>(v);
}

double number_field(const val& object, const char* key, const std::string& where) {
  const val v = object[key];
  if (!is_number(v))
    throw geolens::InvalidInput(where + ": '" + key + "' must be a number, got " +
                                v.typeOf().as<std::string>());
  return v.as<double>();
}

// One lens of the JS array: {kind:'circle', cx, cy, r, zoom} or
// {kind:'polygon', points:[x0, y0, x1, y1, ...], zoom}; zoom defaults to Lens's (2), and
// `profile` ('gaussian', 'sphere', 'mesa') and `footprint` may be given.
geolens::Lens lens_from(const val& spec, size_t index) {
  const std::string where = "Session.update: lens " + std::to_string(index + 1);
  if (spec.typeOf().as<std::string>() != "object" || spec.isNull())
    throw geolens::InvalidInput(where + " must be an object");
  const val kind_value = spec["kind"];
  const std::string kind =
      kind_value.isString() ? kind_value.as<std::string>() : std::string("(none)");
  std::optional<geolens::Region> region;
  if (kind == "circle") {
    region =
        geolens::Region::circle({number_field(spec, "cx", where), number_field(spec, "cy", where)},
                                number_field(spec, "r", where));
  } else if (kind == "polygon") {
    const std::vector<double> xy = numbers_from(spec["points"], where + ": points");
    if (xy.size() % 2 != 0)
      throw geolens::InvalidInput(where + ": points must be x, y pairs, got " +
                                  std::to_string(xy.size()) + " numbers");
    std::vector<Eigen::Vector2d> vertices;
    for (size_t i = 0; i + 1 < xy.size(); i += 2) vertices.emplace_back(xy[i], xy[i + 1]);
    region = geolens::Region::polygon(vertices);
  } else {
    throw geolens::InvalidInput(where + ": kind must be 'circle' or 'polygon', got '" + kind + "'");
  }
  geolens::Lens lens{*region};
  if (!spec["zoom"].isUndefined()) lens.zoom = number_field(spec, "zoom", where);
  if (!spec["profile"].isUndefined())
    lens.profile = geolens::parse_profile(spec["profile"].as<std::string>());
  if (!spec["footprint"].isUndefined()) lens.footprint = number_field(spec, "footprint", where);
  return lens;
}

// LensOptions from a number (the mesh) or an object of options named as the library's option
// table names them (lens_option_fields: mesh, model, mesh_tolerance, draft_mesh, ...), each set
// from its text as every face sets it (so their checks and messages are the library's).
geolens::LensOptions options_from(const val& mesh_or_options) {
  geolens::LensOptions options;
  options.flatten.threads = 1;  // a build without -pthread has no other thread
  if (mesh_or_options.isUndefined() || mesh_or_options.isNull()) return options;
  if (is_number(mesh_or_options)) {
    geolens::lens_option_field("mesh").set(
        options, val::global("String")(mesh_or_options).as<std::string>());
    return options;
  }
  const val keys = val::global("Object").call<val>("keys", mesh_or_options);
  const int n = keys["length"].as<int>();
  for (int i = 0; i < n; ++i) {
    const std::string key = keys[i].as<std::string>();
    if (key == "width" || key == "height") continue;  // session({width, height, ...})
    const std::string text = val::global("String")(mesh_or_options[key]).as<std::string>();
    geolens::lens_option_field(key).set(options, text);
  }
  // A session keeps its mesh from frame to frame (LensSession): silently ignored, the option
  // gave warps up to 34 px from the CLI's. Checked once the values are (as the CLI checks them).
  geolens::validate(options);
  geolens::require_option(options.subdivision.max_levels == 0, "Session", "subdivide",
                          "must be 0: a session keeps its mesh from frame to frame and does "
                          "not subdivide it");
  return options;
}

// `size` as a width or height of pixels: a whole number in [1, 2^20]; InvalidInput otherwise.
int pixel_count(double size, const char* name) {
  if (!(size >= 1 && size <= double(1 << 20) && size == std::floor(size)))
    throw geolens::InvalidInput(std::string("Session: ") + name +
                                " must be a whole number of pixels in [1, 1048576], got " +
                                geolens::number_text(size));
  return int(size);
}

}  // namespace

// One lens session on a width x height image: LensSession (the interactive face of the
// geometric lens) plus the last frame's warp, in the layouts a renderer wants, and its WarpMap.
// Every method returns its answer or a JS Error (guarded); post.js throws the Error.
class SessionCore {
 public:
  SessionCore() = default;

  // Starts the session (LensSession(width, height, options)); undefined or an Error.
  val init(double width, double height, val mesh_or_options) {
    return guarded([&] {
      const int w = pixel_count(width, "width"), h = pixel_count(height, "height");
      geolens::LensOptions options = options_from(mesh_or_options);
      session_.emplace(w, h, options);
      width_ = w, height_ = h;
      return val::undefined();
    });
  }

  // Solves `lenses` (a JS array) and returns the frame: pointers and counts into the wasm heap
  // (post.js makes the typed-array views) and per lens what was asked and what was got.
  val update(val lenses, bool draft) {
    return guarded([&] {
      if (!session_) throw geolens::InvalidInput("Session.update: the session is disposed");
      std::vector<geolens::Lens> list;
      if (!val::global("Array").call<bool>("isArray", lenses))
        throw geolens::InvalidInput("Session.update: lenses must be an array");
      const int n = lenses["length"].as<int>();
      for (int i = 0; i < n; ++i) list.push_back(lens_from(lenses[i], size_t(i)));
      geolens::LensResult result = session_->update(list, {}, draft);
      store(result.warp);
      // The map's indexes are made on the first forward() or inverse() of this frame: a drag
      // that maps no point does not pay for them (a fifth of a circle's frame).
      warp_ = result.warp;
      map_.reset();

      val frame = val::object();
      frame.set("positionsPtr", uintptr_t(positions_.data()));
      frame.set("texcoordsPtr", uintptr_t(texcoords_.data()));
      frame.set("trianglesPtr", uintptr_t(triangles_.data()));
      frame.set("vertexCount", double(positions_.size() / 2));
      frame.set("triangleCount", double(triangles_.size() / 3));
      frame.set("screenWidth", result.warp.screen_width);
      frame.set("screenHeight", result.warp.screen_height);
      frame.set("draft", result.draft);
      frame.set("model", geolens::to_string(result.model));
      val per_lens = val::array();
      for (size_t k = 0; k < list.size(); ++k) {
        val lens = val::object();
        lens.set("zoomAsked", list[k].zoom);
        lens.set("zoomGot", k < result.zoom_measured.size() ? result.zoom_measured[k] : NAN);
        lens.set("zoomFit", k < result.zoom_fits.size() ? val(result.zoom_fits[k]) : val::null());
        lens.set("reason",
                 k < result.zoom_fit_reasons.size() ? result.zoom_fit_reasons[k] : std::string());
        per_lens.call<void>("push", lens);
      }
      frame.set("lenses", per_lens);
      val warnings = val::array();
      for (const std::string& w : geolens::zoom_warnings(list, result))
        warnings.call<void>("push", w);
      frame.set("warnings", warnings);
      return frame;
    });
  }

  // Source -> screen pixels of the points [x0, y0, x1, y1, ...] (a Float64Array or an array):
  // a new Float64Array of the same length, NaN where a point is in no triangle.
  val forward(val points) const { return map_points(points, true); }
  // Screen -> source pixels, as forward().
  val inverse(val points) const { return map_points(points, false); }

  // Forgets every frame (LensSession::reset); the warp stays until the next update().
  val reset() {
    return guarded([&] {
      if (session_) session_->reset();
      return val::undefined();
    });
  }

 private:
  void store(const geolens::WarpMesh& warp) {
    const Eigen::Index v = warp.source.rows(), f = warp.F.rows();
    positions_.resize(size_t(2 * v));
    texcoords_.resize(size_t(2 * v));
    triangles_.resize(size_t(3 * f));
    for (Eigen::Index i = 0; i < v; ++i) {
      positions_[size_t(2 * i)] = warp.screen(i, 0);
      positions_[size_t(2 * i + 1)] = warp.screen(i, 1);
      texcoords_[size_t(2 * i)] = warp.source(i, 0);
      texcoords_[size_t(2 * i + 1)] = warp.source(i, 1);
    }
    for (Eigen::Index t = 0; t < f; ++t)
      for (int c = 0; c < 3; ++c) triangles_[size_t(3 * t + c)] = uint32_t(warp.F(t, c));
  }

  val map_points(const val& points, bool forward) const {
    return guarded([&] {
      const std::string name = forward ? "Session.forward" : "Session.inverse";
      if (!warp_) throw geolens::InvalidInput(name + ": no frame yet: call update() first");
      if (!map_) map_ = geolens::framed_warp_map(*warp_, width_, height_);
      const std::vector<double> xy = numbers_from(points, name + ": points");
      if (xy.size() % 2 != 0)
        throw geolens::InvalidInput(name + ": points must be x, y pairs, got " +
                                    std::to_string(xy.size()) + " numbers");
      const Eigen::Index n = Eigen::Index(xy.size() / 2);
      Eigen::MatrixX2d in(n, 2);
      for (Eigen::Index i = 0; i < n; ++i)
        in(i, 0) = xy[size_t(2 * i)], in(i, 1) = xy[size_t(2 * i + 1)];
      const Eigen::MatrixX2d out = forward ? map_->forward_batch(in) : map_->inverse_batch(in);
      std::vector<double> flat(xy.size());
      for (Eigen::Index i = 0; i < n; ++i)
        flat[size_t(2 * i)] = out(i, 0), flat[size_t(2 * i + 1)] = out(i, 1);
      // A copy (new Float64Array(view)): it stays valid whatever the heap does next.
      return val::global("Float64Array")
          .new_(emscripten::typed_memory_view(flat.size(), flat.data()));
    });
  }

  std::optional<geolens::LensSession> session_;
  int width_ = 0, height_ = 0;
  std::vector<double> positions_, texcoords_;    // #V x 2 interleaved: screen, source pixels
  std::vector<uint32_t> triangles_;              // #F x 3 interleaved vertex indices
  std::optional<geolens::WarpMesh> warp_;        // the last frame's
  mutable std::optional<geolens::WarpMap> map_;  // of warp_, framed at width x height; lazily
};

// The library's number_text, for tests of messages.
std::string number_text(double value) { return geolens::number_text(value); }

// Bytes malloc has handed out and not had back (dlmalloc's mallinfo): for leak tests.
double heap_in_use() { return double(mallinfo().uordblks); }

EMSCRIPTEN_BINDINGS(geolens) {
  emscripten::class_<SessionCore>("SessionCore")
      .constructor<>()
      .function("init", &SessionCore::init)
      .function("update", &SessionCore::update)
      .function("forward", &SessionCore::forward)
      .function("inverse", &SessionCore::inverse)
      .function("reset", &SessionCore::reset);
  emscripten::function("numberText", &number_text);
  emscripten::function("heapInUse", &heap_in_use);
}

#include "specula/gl/context.h"

#include <algorithm>
#include <cstdlib>
#include <fmt/format.h>
#include <string>
#include <vector>

#include "gl_api.h"
#include "target.h"

namespace specula::gl {
namespace {

bool has_extension(const char* list, std::string_view name) {
  if (list == nullptr) return false;
  const std::string_view all(list);
  for (std::size_t start = 0; start < all.size();) {
    const std::size_t end = std::min(all.find(' ', start), all.size());
    if (all.substr(start, end - start) == name) return true;
    start = end + 1;
  }
  return false;
}

std::string egl_error_text() { return fmt::format("EGL error 0x{:04x}", eglGetError()); }

// EGL hands every caller the same display, and eglTerminate ends it for the whole process (any
// other Context on it included); Mesa then also unloads its driver, whose globals own memory
// that llvmpipe never frees (LeakSanitizer reports it once the library is gone). So a display,
// once initialized, stays so until the process ends; eglInitialize on it again is a no-op.
bool initialize(EGLDisplay display) {
  EGLint major = 0, minor = 0;
  return eglInitialize(display, &major, &minor) == EGL_TRUE;
}

struct Candidate {
  EGLDisplay display;
  std::string platform;
};

// Which displays to try: SPECULA_EGL_PLATFORM = "device" or "surfaceless" keeps only those.
struct Platforms {
  bool device = true;
  bool surfaceless = true;
};

Platforms platforms_from_environment() {
  const char* chosen = std::getenv("SPECULA_EGL_PLATFORM");
  if (chosen == nullptr || *chosen == '\0') return {};
  const std::string_view name(chosen);
  if (name == "device") return {true, false};
  if (name == "surfaceless") return {false, true};
  throw GlError(fmt::format("SPECULA_EGL_PLATFORM '{}' is unknown: expected device or surfaceless", name));
}

// Hardware devices first (EGL_EXT_platform_device), then Mesa's surfaceless platform.
std::vector<Candidate> candidate_displays(const Platforms& platforms) {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  std::vector<Candidate> candidates;
  if (platforms.device && has_extension(client, "EGL_EXT_device_enumeration") &&
      has_extension(client, "EGL_EXT_platform_device")) {
    const auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    const auto device_string =
        reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
    std::vector<EGLDeviceEXT> devices(16);
    EGLint count = 0;
    if (query_devices && device_string && query_devices(static_cast<EGLint>(devices.size()), devices.data(), &count)) {
      for (EGLint i = 0; i < count; ++i) {
        const char* extensions = device_string(devices[i], EGL_EXTENSIONS);
        if (has_extension(extensions, "EGL_MESA_device_software")) continue;
        const char* file = has_extension(extensions, "EGL_EXT_device_drm")
                               ? device_string(devices[i], EGL_DRM_DEVICE_FILE_EXT) : nullptr;
        const EGLDisplay display = eglGetPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (display != EGL_NO_DISPLAY)
          candidates.push_back({display, file ? fmt::format("EGL device {}", file) : fmt::format("EGL device {}", i)});
      }
    }
  }
  if (platforms.surfaceless && has_extension(client, "EGL_MESA_platform_surfaceless")) {
    const EGLDisplay display = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display != EGL_NO_DISPLAY) candidates.push_back({display, "Mesa surfaceless"});
  }
  return candidates;
}

// A 3.3 core context on an initialized display, without a config where the display allows it.
EGLContext create_core_context(EGLDisplay display, std::string& why) {
  const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
  if (!has_extension(extensions, "EGL_KHR_surfaceless_context")) {
    why = "no EGL_KHR_surfaceless_context";
    return EGL_NO_CONTEXT;
  }
  if (!eglBindAPI(EGL_OPENGL_API)) {
    why = "no desktop OpenGL (eglBindAPI)";
    return EGL_NO_CONTEXT;
  }
  EGLConfig config = EGL_NO_CONFIG_KHR;
  if (!has_extension(extensions, "EGL_KHR_no_config_context")) {
    const EGLint wanted[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, 0, EGL_NONE};
    EGLint found = 0;
    if (!eglChooseConfig(display, wanted, &config, 1, &found) || found < 1) {
      why = "no EGL config for desktop OpenGL";
      return EGL_NO_CONTEXT;
    }
  }
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  const EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, attributes);
  if (context == EGL_NO_CONTEXT) why = "no OpenGL 3.3 core context (" + egl_error_text() + ")";
  return context;
}

std::string gl_string(GLenum name) {
  const auto* text = reinterpret_cast<const char*>(glGetString(name));
  return text ? text : "?";
}

ContextInfo query_info(std::string platform) {
  ContextInfo info{std::move(platform), gl_string(GL_VENDOR), gl_string(GL_RENDERER), gl_string(GL_VERSION)};
  GLint viewport[2] = {0, 0};
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &info.max_texture_size);
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
  info.max_viewport_width = viewport[0];
  info.max_viewport_height = viewport[1];
  return info;
}

}  // namespace

struct Context::Egl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  GLuint vertex_array = 0;  // a core profile draws nothing without a bound VAO
  std::unique_ptr<Target> target;

  ~Egl() {
    if (context != EGL_NO_CONTEXT) {
      if (vertex_array != 0 && eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
        target.reset();
        glDeleteVertexArrays(1, &vertex_array);
      }
      eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      eglDestroyContext(display, context);
    }
  }
};

std::string to_string(const ContextInfo& info) {
  return fmt::format("{} ({}; {})", info.renderer, info.version, info.platform);
}

Context::Context() {
  const Platforms platforms = platforms_from_environment();
  std::vector<std::string> failures;
  for (const Candidate& candidate : candidate_displays(platforms)) {
    if (!initialize(candidate.display)) {
      failures.push_back(fmt::format("{}: eglInitialize failed ({})", candidate.platform, egl_error_text()));
      continue;
    }
    auto egl = std::make_unique<Egl>();
    egl->display = candidate.display;
    std::string why;
    egl->context = create_core_context(candidate.display, why);
    if (egl->context != EGL_NO_CONTEXT &&
        !eglMakeCurrent(candidate.display, EGL_NO_SURFACE, EGL_NO_SURFACE, egl->context))
      why = "eglMakeCurrent failed (" + egl_error_text() + ")";
    if (!why.empty()) {
      failures.push_back(fmt::format("{}: {}", candidate.platform, why));
      continue;  // ~Egl releases what was made
    }
    glGenVertexArrays(1, &egl->vertex_array);
    glBindVertexArray(egl->vertex_array);
    egl_ = std::move(egl);
    info_ = query_info(candidate.platform);
    return;
  }
  if (failures.empty())
    failures.push_back(platforms.surfaceless ? (platforms.device ? "EGL lists neither a GPU device nor Mesa's surfaceless platform"
                                                                 : "EGL does not offer Mesa's surfaceless platform")
                                             : "EGL lists no device but Mesa's software one (SPECULA_EGL_PLATFORM=device)");
  std::string reasons;
  for (const auto& f : failures) reasons += (reasons.empty() ? "" : "; ") + f;
  throw GlError("OpenGL is not available: " + reasons);
}

Context::~Context() = default;

Target& Context::target(int width, int height) const {
  make_current();
  if (!egl_->target || egl_->target->width() != width || egl_->target->height() != height) {
    egl_->target.reset();
    egl_->target = std::make_unique<Target>(width, height);
  }
  egl_->target->bind();
  return *egl_->target;
}

void Context::make_current() const {
  if (eglGetCurrentContext() == egl_->context) return;
  if (!eglMakeCurrent(egl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, egl_->context))
    throw GlError("cannot make the OpenGL context current (" + egl_error_text() + ")");
}

}  // namespace specula::gl

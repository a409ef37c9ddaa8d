// SPDX-License-Identifier: GPL-3.0-or-later
#include "egl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>

#include <cstdio>
#include <cstring>
#include <vector>

namespace unimouse {
namespace {

std::string ErrorText(const char* what) {
  char text[96];
  std::snprintf(text, sizeof(text), "%s failed (EGL error 0x%04x)", what, eglGetError());
  return text;
}

bool HasExtension(const char* list, const char* name) {
  if (list == nullptr) return false;
  const size_t n = std::strlen(name);
  for (const char* p = std::strstr(list, name); p != nullptr; p = std::strstr(p + n, name)) {
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  }
  return false;
}

// a display on a hardware device (one with a DRM node), as NVIDIA's driver offers
EGLDisplay HardwareDeviceDisplay() {
  auto query_devices =
      reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  auto query_string = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
      eglGetProcAddress("eglQueryDeviceStringEXT"));
  if (query_devices == nullptr || query_string == nullptr) return EGL_NO_DISPLAY;
  EGLint count = 0;
  if (!query_devices(0, nullptr, &count) || count <= 0) return EGL_NO_DISPLAY;
  std::vector<EGLDeviceEXT> devices(static_cast<size_t>(count));
  if (!query_devices(count, devices.data(), &count)) return EGL_NO_DISPLAY;
  for (int i = 0; i < count; ++i) {
    if (!HasExtension(query_string(devices[i], EGL_EXTENSIONS), "EGL_EXT_device_drm")) continue;
    EGLDisplay display = eglGetPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
    if (display != EGL_NO_DISPLAY && eglInitialize(display, nullptr, nullptr)) return display;
  }
  return EGL_NO_DISPLAY;
}

}  // namespace

std::unique_ptr<EglContext> EglContext::Create() {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  // EGL 1.5 platform displays, as glvnd's libEGL has: the platform is named here, in code
  if (client == nullptr || !HasExtension(client, "EGL_EXT_platform_base")) {
    throw RenderUnavailable(
        "no EGL display: no EGL driver with platform displays (install "
        "libegl-mesa0)");
  }
  EGLDisplay display = EGL_NO_DISPLAY;
  if (HasExtension(client, "EGL_EXT_platform_device")) display = HardwareDeviceDisplay();
  if (display == EGL_NO_DISPLAY) {
    if (!HasExtension(client, "EGL_MESA_platform_surfaceless")) {
      throw RenderUnavailable(
          "no EGL display: no GPU device and no Mesa surfaceless platform "
          "(install libegl-mesa0 and libgl1-mesa-dri)");
    }
    display = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display == EGL_NO_DISPLAY || !eglInitialize(display, nullptr, nullptr)) {
      throw RenderUnavailable("no EGL display: " +
                              ErrorText("initialising Mesa's surfaceless display"));
    }
  }
  std::unique_ptr<EglContext> c(new EglContext);
  c->display_ = display;
  // MuJoCo draws into its own framebuffer object, so the context needs no surface
  const EGLint attributes[] = {EGL_RED_SIZE,
                               8,
                               EGL_GREEN_SIZE,
                               8,
                               EGL_BLUE_SIZE,
                               8,
                               EGL_DEPTH_SIZE,
                               24,
                               EGL_STENCIL_SIZE,
                               8,
                               EGL_SURFACE_TYPE,
                               EGL_PBUFFER_BIT,
                               EGL_RENDERABLE_TYPE,
                               EGL_OPENGL_BIT,
                               EGL_NONE};
  EGLConfig config = nullptr;
  EGLint configs = 0;
  if (!eglChooseConfig(display, attributes, &config, 1, &configs) || configs < 1) {
    throw RenderUnavailable("no EGL display: " + ErrorText("choosing an OpenGL configuration"));
  }
  if (!eglBindAPI(EGL_OPENGL_API)) {
    throw RenderUnavailable("no EGL display: " + ErrorText("binding desktop OpenGL"));
  }
  c->context_ = eglCreateContext(display, config, EGL_NO_CONTEXT, nullptr);
  if (c->context_ == EGL_NO_CONTEXT) {
    throw RenderUnavailable("no EGL display: " + ErrorText("creating an OpenGL context"));
  }
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, c->context_)) {
    throw RenderUnavailable("no EGL display: " + ErrorText("making the context current"));
  }
  const auto* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  c->renderer_ = name != nullptr ? name : "unknown";
  return c;
}

void EglContext::MakeCurrent() const {
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_);
}

void EglContext::Release() const {
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

EglContext::~EglContext() {
  if (display_ == nullptr) return;
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  if (context_ != nullptr) eglDestroyContext(display_, context_);

  // no eglTerminate: every context of the process shares the one display EGL hands out, so
  // terminating it here would pull it from under any other; it lasts until the process ends,
  // and so does the driver it loaded (unloading it would strand what the driver allocated)
}

}  // namespace unimouse

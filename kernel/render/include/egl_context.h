// SPDX-License-Identifier: GPL-3.0-or-later
// A headless OpenGL context for offscreen pictures, with no window system: a GPU through EGL's
// device platform when the machine has one, otherwise Mesa's surfaceless platform (a render
// node, or the llvmpipe software renderer). The platform is chosen in code through
// eglGetPlatformDisplay, never through environment variables.
#ifndef UNIMOUSE_RENDER_EGL_CONTEXT_H_
#define UNIMOUSE_RENDER_EGL_CONTEXT_H_

#include <memory>
#include <string>

#include "unimouse/errors.h"

namespace unimouse {

/// The machine cannot draw pictures; a bad-input error (exit code 2) for whoever asked for one.
class RenderUnavailable : public InputError {
 public:
  using InputError::InputError;
};

class EglContext {
 public:
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;
  ~EglContext();

  /// Creates a context and leaves it current on this thread. Throws RenderUnavailable saying
  /// why, in one line, when the machine has no usable EGL display. The display is initialised
  /// once and stays so until the process ends; a context is destroyed with its EglContext.
  static std::unique_ptr<EglContext> Create();

  /// Makes the context current on this thread, or lets go of it. A thread holds one context at
  /// a time, and a viewer's window has one too: each lets go when it has drawn.
  void MakeCurrent() const;
  void Release() const;

  /// The GL renderer's name, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  const std::string& renderer() const { return renderer_; }

 private:
  EglContext() = default;
  void* display_ = nullptr;
  void* context_ = nullptr;
  std::string renderer_;
};

}  // namespace unimouse

#endif  // UNIMOUSE_RENDER_EGL_CONTEXT_H_

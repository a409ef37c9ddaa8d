// SPDX-License-Identifier: GPL-3.0-or-later
#include "firmware_command.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <thread>
#include <vector>

#include "command_line.h"
#include "install_paths.h"
#include "text_file.h"
#include "transport_spec.h"
#include "unimouse/errors.h"

extern char** environ;

namespace unimouse {
namespace {

namespace fs = std::filesystem;

// the sketch's file: NAME/NAME.ino for a folder, as the Arduino IDE lays sketches out
fs::path SketchFile(const std::string& sketch) {
  const fs::path path = fs::absolute(sketch).lexically_normal();
  if (IsDirectory(path)) {
    const fs::path folder = path.has_filename() ? path : path.parent_path();
    const fs::path ino = folder / (folder.filename().string() + ".ino");
    if (!IsRegularFile(ino)) {
      throw InputError(sketch + ": a sketch folder holds a sketch of its name, " +
                       ino.filename().string() + ", and this one does not");
    }
    return ino;
  }
  if (!IsRegularFile(path)) throw InputError(sketch + ": no such sketch file or folder");
  const std::string extension = path.extension().string();
  if (extension != ".ino" && extension != ".cc" && extension != ".cpp") {
    throw InputError(sketch + ": a sketch is an .ino file (or a .cc or .cpp written like one)");
  }
  return path;
}

bool OnPath(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    if (!dir.empty() && ::access((fs::path(dir) / program).c_str(), X_OK) == 0) return true;
  }
  return false;
}

// runs a program with this process's output, and returns its exit status
int Run(const std::vector<std::string>& words) {
  std::vector<char*> argv;
  for (const auto& w : words) argv.push_back(const_cast<char*>(w.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (::posix_spawnp(&pid, argv[0], nullptr, nullptr, argv.data(), environ) != 0) return 127;
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// a CMake bracket argument holds any text but its own closing bracket
std::string CMakeQuoted(const std::string& text) {
  std::string equals = "=";
  while (text.find("]" + equals + "]") != std::string::npos) equals += "=";
  return "[" + equals + "[" + text + "]" + equals + "]";
}

}  // namespace

int FirmwareBuild(const FirmwareBuildOptions& options) {
  const fs::path sketch = SketchFile(options.sketch);
  const std::string name = options.name.empty() ? sketch.stem().string() : options.name;
  if (name.empty() || name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                             "0123456789_-") != std::string::npos) {
    throw InputError("firmware name '" + name +
                     "': use letters, digits, _ and - only (--name sets another)");
  }
  const bool avr = options.board == "mega2560";
  if (!avr && options.board != "pc") {
    throw InputError("--board " + options.board + ": the boards are pc and mega2560");
  }
  const fs::path config = FirmwareCMakeDirectory();
  if (!IsRegularFile(config / "UnimouseFirmwareConfig.cmake")) {
    throw InputError("the Arduino library is not installed (no " + config.string() +
                     "/UnimouseFirmwareConfig.cmake): install the arduino-unimousesim package");
  }
  for (const char* tool : {"cmake", avr ? "avr-g++" : "c++"}) {
    if (!OnPath(tool)) {
      throw InputError(std::string("firmware build needs ") + tool + " (apt install " +
                       (avr ? "cmake gcc-avr avr-libc arduino-core-avr" : "cmake g++ make") + ")");
    }
  }

  // by default the built files go beside the sketch file: into the sketch's own folder, where
  // the program of the sketch folder's name cannot collide with the folder itself
  const fs::path out = options.out_dir.empty() ? sketch.parent_path()
                                               : fs::absolute(options.out_dir).lexically_normal();
  if (!avr && IsDirectory(out / name)) {
    throw InputError((out / name).string() + " is a directory, so the built program cannot go " +
                     "there: give --out another directory or --name another name");
  }
  const fs::path work = out / ".unimouse-build" / (name + "-" + options.board);
  fs::create_directories(work);
  // a project of two lines, as a student's own CMake project would have it
  std::ofstream project(work / "CMakeLists.txt");
  project << "# written by unimouse firmware build\n"
          << "cmake_minimum_required(VERSION 3.25)\n"
          << "project(" << (avr ? "firmware NONE" : "firmware C CXX") << ")\n"
          << "find_package(UnimouseFirmware REQUIRED PATHS " << CMakeQuoted(config.string())
          << " NO_DEFAULT_PATH)\n";
  if (avr) {
    project << "unimouse_add_avr_firmware(firmware SKETCHES "
            << CMakeQuoted(name + "=" + sketch.string()) << " OUTPUT_DIRECTORY "
            << CMakeQuoted(out.string()) << ")\n";
  } else {
    project << "unimouse_add_firmware(firmware " << CMakeQuoted(sketch.string())
            << " OUTPUT_DIRECTORY " << CMakeQuoted(out.string()) << ")\n"
            << "set_target_properties(firmware firmware_module PROPERTIES OUTPUT_NAME "
            << CMakeQuoted(name) << ")\n";
  }
  project.close();
  if (!project) throw InputError("cannot write " + (work / "CMakeLists.txt").string());

  const std::string jobs = std::to_string(std::max(1u, std::thread::hardware_concurrency()));
  const std::string build = (work / "build").string();
  // for the PC the program first: a sketch that does not compile says so once, not also for
  // the module made of the same source
  if (Run({"cmake", "-S", work.string(), "-B", build, "-Wno-dev",
           "-DCMAKE_BUILD_TYPE=RelWithDebInfo"}) != 0 ||
      (!avr && Run({"cmake", "--build", build, "-j", jobs, "--target", "firmware"}) != 0) ||
      Run({"cmake", "--build", build, "-j", jobs}) != 0) {
    throw InputError(options.sketch + ": the sketch did not build (the messages are above)");
  }
  using link::FirmwareHost;
  using link::FirmwareSpec;
  if (avr) {
    const std::string image = (out / (name + ".elf")).string();
    std::printf("built %s\nrun it on the emulated board: unimouse run --link %s --scenario ...\n",
                image.c_str(), FirmwareSpec(FirmwareHost::kEmulatedBoard, image).c_str());
  } else {
    const std::string program = (out / name).string(), module = program + ".so";
    std::printf(
        "built %s and %s\nrun it: unimouse run --link %s --scenario ...\n"
        "or in the simulator's process, faster: --link %s\n",
        program.c_str(), module.c_str(), FirmwareSpec(FirmwareHost::kProcess, program).c_str(),
        FirmwareSpec(FirmwareHost::kInProcess, module).c_str());
  }
  return kExitPassed;
}

void AddFirmwareCommands(CommandLine& cli) {
  auto firmware = std::make_shared<FirmwareBuildOptions>();
  CLI::App* firmware_cmd =
      cli.app().add_subcommand("firmware", "build a sketch written against the Arduino library");
  firmware_cmd->require_subcommand(1);
  CLI::App* firmware_build_cmd = firmware_cmd->add_subcommand(
      "build",
      "build a sketch for the PC (a program and a module, each run in lock-step by --link) or "
      "for the emulated board (an image for --link), docs/firmware.md");
  firmware_build_cmd->add_option("sketch", firmware->sketch, "sketch folder or .ino file")
      ->required();
  firmware_build_cmd->add_option(
      "--out", firmware->out_dir,
      "directory for the built files (default: the sketch's folder; the build tree goes "
      "in its .unimouse-build)");
  firmware_build_cmd
      ->add_option("--board", firmware->board, "pc, or mega2560 for the emulated board")
      ->capture_default_str();
  firmware_build_cmd->add_option("--name", firmware->name,
                                 "name of the built files (default: the sketch's)");

  cli.Add(firmware_build_cmd, [firmware] { return FirmwareBuild(*firmware); });
}

}  // namespace unimouse

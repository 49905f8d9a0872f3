#include "engine/gpu/shader_compiler.hpp"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>
#include <glslang/build_info.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <regex>
#include <sstream>

#include "engine/gpu/shader_includer.hpp"

#ifndef VOXGI_SHADER_ROOT
#define VOXGI_SHADER_ROOT "shaders"
#endif

namespace voxgi::gpu {

namespace fs = std::filesystem;

namespace {

// Part of every cache key: a change here or in glslang invalidates old entries.
const std::string& compiler_version() {
  static const std::string version =
      "voxgi-spirv-cache-1 glslang " + std::to_string(GLSLANG_VERSION_MAJOR) + "." +
      std::to_string(GLSLANG_VERSION_MINOR) + "." + std::to_string(GLSLANG_VERSION_PATCH) +
      " vulkan1.3 spirv1.6 glsl460";
  return version;
}

void initialize_glslang() {
  static std::once_flag once;
  std::call_once(once, [] { glslang::InitializeProcess(); });
}

// Two FNV-1a 64 lanes with different bases: a 128-bit key, so collisions are not a concern.
struct Hasher {
  uint64_t a = 0xcbf29ce484222325ull;
  uint64_t b = 0x84222325cbf29ce4ull;
  void add(const void* data, size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) {
      a = (a ^ bytes[i]) * 0x100000001b3ull;
      b = (b ^ bytes[i]) * 0x100000001b3ull;
      b ^= b >> 29;
    }
  }
  void add(const std::string& text) {
    uint64_t size = text.size();
    add(&size, sizeof(size));
    add(text.data(), text.size());
  }
  std::string hex() const {
    char text[33];
    std::snprintf(text, sizeof(text), "%016llx%016llx", static_cast<unsigned long long>(a),
                  static_cast<unsigned long long>(b));
    return text;
  }
};

uint64_t checksum(const std::vector<uint32_t>& words) {
  Hasher hasher;
  hasher.add(words.data(), words.size() * sizeof(uint32_t));
  return hasher.a;
}

// Cache file: a 16-byte header (tag, word count, checksum of the words) then the SPIR-V, so a
// truncated or damaged entry is detected and recompiled.
constexpr uint32_t kCacheTag = 0x56584753;  // "SGXV"

std::optional<std::vector<uint32_t>> read_cache(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return std::nullopt;
  uint32_t tag = 0, count = 0;
  uint64_t sum = 0;
  file.read(reinterpret_cast<char*>(&tag), 4);
  file.read(reinterpret_cast<char*>(&count), 4);
  file.read(reinterpret_cast<char*>(&sum), 8);
  if (!file || tag != kCacheTag || count < 5 || count > (64u << 20)) return std::nullopt;
  std::vector<uint32_t> words(count);
  file.read(reinterpret_cast<char*>(words.data()), std::streamsize(count) * 4);
  if (!file || file.peek() != std::char_traits<char>::eof()) return std::nullopt;
  if (words[0] != 0x07230203u || checksum(words) != sum) return std::nullopt;
  return words;
}

void write_cache(const fs::path& dir, const fs::path& path, const std::vector<uint32_t>& words) {
  static std::atomic<uint64_t> counter{0};
  std::error_code error;
  fs::create_directories(dir, error);
  fs::path temp = path;
  temp += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
  {
    std::ofstream file(temp, std::ios::binary | std::ios::trunc);
    if (!file) return;  // a read-only cache only costs compile time
    uint32_t tag = kCacheTag, count = static_cast<uint32_t>(words.size());
    uint64_t sum = checksum(words);
    file.write(reinterpret_cast<const char*>(&tag), 4);
    file.write(reinterpret_cast<const char*>(&count), 4);
    file.write(reinterpret_cast<const char*>(&sum), 8);
    file.write(reinterpret_cast<const char*>(words.data()), std::streamsize(words.size()) * 4);
    if (!file) {
      file.close();
      fs::remove(temp, error);
      return;
    }
  }
  fs::rename(temp, path, error);
  if (error) fs::remove(temp, error);
}

EShLanguage glslang_stage(VkShaderStageFlagBits stage) {
  switch (stage) {
    case VK_SHADER_STAGE_VERTEX_BIT:
      return EShLangVertex;
    case VK_SHADER_STAGE_GEOMETRY_BIT:
      return EShLangGeometry;
    case VK_SHADER_STAGE_FRAGMENT_BIT:
      return EShLangFragment;
    case VK_SHADER_STAGE_COMPUTE_BIT:
      return EShLangCompute;
    case VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT:
      return EShLangTessControl;
    case VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT:
      return EShLangTessEvaluation;
    default:
      return EShLangCount;
  }
}

// Rewrites glslang's "ERROR: file:line: 'token' : message" lines as
// "file:line: error: 'token' : message", with the include chain for included files.
std::string format_log(const std::string& log, const std::string& main_file,
                       const ShaderIncluder* includer) {
  static const std::regex located(R"(^(ERROR|WARNING): (.+):(\d+): (.*)$)");
  static const std::regex unlocated(R"(^(ERROR|WARNING): (.*)$)");
  std::istringstream lines(log);
  std::string line, out;
  while (std::getline(lines, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::smatch match;
    while (!line.empty() && (line.back() == ' ' || line.back() == '\t')) line.pop_back();
    if (std::regex_match(line, match, located)) {
      if (match[1] != "ERROR") continue;
      // glslang's "compilation terminated" follow-up says nothing new.
      if (match[4].str().find("compilation terminated") != std::string::npos) continue;
      std::string file = match[2];
      out += file + ":" + match[3].str() + ": error: " + match[4].str() + "\n";
      std::string chain = includer ? includer->include_chain(file) : "";
      if (!chain.empty()) out += "  (" + chain + ")\n";
    } else if (std::regex_match(line, match, unlocated)) {
      if (match[1] != "ERROR") continue;
      std::string message = match[2];
      // glslang's summary line says nothing new.
      if (message.find("compilation errors.") != std::string::npos) continue;
      out += main_file + ": error: " + message + "\n";
    }
  }
  if (out.empty()) out = main_file + ": error: " + log + "\n";
  if (!out.empty() && out.back() == '\n') out.pop_back();
  return out;
}

std::string getenv_string(const char* name) {
  const char* value = std::getenv(name);
  return value ? value : "";
}

}  // namespace

ShaderCompiler::ShaderCompiler(std::vector<fs::path> roots, fs::path cache_dir)
    : roots_(std::move(roots)), cache_dir_(std::move(cache_dir)) {
  initialize_glslang();
}

fs::path ShaderCompiler::default_shader_root() {
  std::string env = getenv_string("VOXGI_SHADER_DIR");
  return env.empty() ? fs::path(VOXGI_SHADER_ROOT) : fs::path(env);
}

fs::path ShaderCompiler::default_cache_dir() {
  std::string env = getenv_string("VOXGI_SHADER_CACHE");
  if (!env.empty()) return env;
  std::string xdg = getenv_string("XDG_CACHE_HOME");
  if (!xdg.empty()) return fs::path(xdg) / "voxgi" / "spirv";
  std::string home = getenv_string("HOME");
  if (!home.empty()) return fs::path(home) / ".cache" / "voxgi" / "spirv";
  std::error_code error;
  return fs::temp_directory_path(error) / "voxgi-spirv";
}

VkShaderStageFlagBits ShaderCompiler::stage_from_extension(const fs::path& path) {
  std::string ext = path.extension().string();
  if (ext == ".vert") return VK_SHADER_STAGE_VERTEX_BIT;
  if (ext == ".geom") return VK_SHADER_STAGE_GEOMETRY_BIT;
  if (ext == ".frag") return VK_SHADER_STAGE_FRAGMENT_BIT;
  if (ext == ".comp") return VK_SHADER_STAGE_COMPUTE_BIT;
  if (ext == ".tesc") return VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT;
  if (ext == ".tese") return VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT;
  return static_cast<VkShaderStageFlagBits>(0);
}

fs::path ShaderCompiler::resolve_main(const fs::path& path) const {
  std::error_code error;
  if (path.is_absolute()) {
    if (fs::is_regular_file(path, error)) return path.lexically_normal();
  } else {
    for (const fs::path& root : roots_) {
      fs::path candidate = (root / path).lexically_normal();
      if (fs::is_regular_file(candidate, error)) return candidate;
    }
  }
  std::string searched;
  if (!path.is_absolute()) {
    for (const fs::path& root : roots_) searched += (searched.empty() ? "" : ", ") + root.string();
  }
  throw Error("shader file not found: " + path.string() +
              (path.is_absolute() ? std::string()
                                  : " (searched the shader roots: " +
                                        (searched.empty() ? std::string("none") : searched) +
                                        "; set VOXGI_SHADER_DIR to the shaders/ folder)"));
}

std::vector<uint32_t> ShaderCompiler::compile(const ShaderRequest& request) {
  const fs::path main = resolve_main(request.path);
  const std::string main_name = main.string();
  VkShaderStageFlagBits stage =
      request.stage != 0 ? request.stage : stage_from_extension(request.path);
  if (stage == 0 || glslang_stage(stage) == EShLangCount) {
    throw Error("shader " + main_name +
                ": cannot tell the stage; expected the extension .vert, .geom, .frag or .comp, "
                "or ShaderRequest::stage");
  }
  auto source = read_text_file(main);
  if (!source) throw Error("shader " + main_name + ": cannot read the file");

  std::string preamble = "#extension GL_GOOGLE_include_directive : require\n";
  for (const ShaderDefine& define : request.defines) {
    if (define.name.empty() || define.name.find_first_of(" \t\n\r()") != std::string::npos) {
      throw Error("shader " + main_name + ": define name \"" + define.name +
                  "\" is not an identifier");
    }
    if (define.value.find('\n') != std::string::npos) {
      throw Error("shader " + main_name + ": define " + define.name +
                  " has a multi-line value; expected one line");
    }
    preamble += "#define " + define.name + " " + (define.value.empty() ? "1" : define.value) + "\n";
  }

  // Cache key: compiler, stage, defines, and the text of every file involved.
  fs::path cache_file;
  if (!cache_dir_.empty()) {
    Hasher hasher;
    hasher.add(compiler_version());
    hasher.add(std::to_string(static_cast<uint32_t>(stage)));
    hasher.add(preamble);
    hasher.add(main_name);
    hasher.add(*source);
    for (const auto& [path, text] : collect_includes(main, *source, roots_)) {
      hasher.add(path.string());
      hasher.add(text);
    }
    cache_file = cache_dir_ / (hasher.hex() + ".spv");
    if (auto cached = read_cache(cache_file)) {
      ++cache_hits_;
      return *cached;
    }
  }

  const EShLanguage language = glslang_stage(stage);
  glslang::TShader shader(language);
  const char* text = source->c_str();
  const int length = static_cast<int>(source->size());
  const char* name = main_name.c_str();
  shader.setStringsWithLengthsAndNames(&text, &length, &name, 1);
  shader.setPreamble(preamble.c_str());
  shader.setEnvInput(glslang::EShSourceGlsl, language, glslang::EShClientVulkan, 100);
  shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_3);
  shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_6);
  const auto messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules);
  ShaderIncluder includer(roots_);
  ++compiled_;
  if (!shader.parse(GetDefaultResources(), 460, ENoProfile, false, false, messages, includer)) {
    throw ShaderError(format_log(shader.getInfoLog(), main_name, &includer));
  }
  glslang::TProgram program;
  program.addShader(&shader);
  if (!program.link(messages)) {
    throw ShaderError(format_log(program.getInfoLog(), main_name, nullptr));
  }
  std::vector<uint32_t> spirv;
  spv::SpvBuildLogger logger;
  glslang::SpvOptions options;
  options.disableOptimizer = true;
  options.validate = false;
  glslang::GlslangToSpv(*program.getIntermediate(language), spirv, &logger, &options);
  std::string errors = logger.getAllMessages();
  if (spirv.empty() || errors.find("error") != std::string::npos) {
    throw ShaderError(main_name + ": error: SPIR-V generation failed: " + errors);
  }
  if (!cache_file.empty()) write_cache(cache_dir_, cache_file, spirv);
  return spirv;
}

}  // namespace voxgi::gpu

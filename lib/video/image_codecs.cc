// OpenCV's imgcodecs loaded on first use; see image_codecs.h.
#include "video/image_codecs.h"

#include <dlfcn.h>

#include "io/error.h"

namespace rk::video {
namespace {

using ImReadFn = cv::Mat (*)(const std::string&, int);
using ImWriteFn = bool (*)(const std::string&, cv::InputArray, const std::vector<int>&);

struct Codecs {
  ImReadFn imread = nullptr;
  ImWriteFn imwrite = nullptr;
};

// The C++ names of cv::imread(const std::string&, int) and cv::imwrite(const std::string&, InputArray,
// const std::vector<int>&) in OpenCV 4 (Itanium ABI, libstdc++'s std::string).
constexpr const char* kImRead = "_ZN2cv6imreadERKNSt7__cxx1112basic_stringIcSt11char_traitsIcESaIcEEEi";
constexpr const char* kImWrite =
    "_ZN2cv7imwriteERKNSt7__cxx1112basic_stringIcSt11char_traitsIcESaIcEEERKNS_11_InputArrayERKSt6vectorIiSaIiEE";

const Codecs& Load() {
  static const Codecs codecs = [] {
    void* lib = ::dlopen(RK_OPENCV_IMGCODECS_SONAME, RTLD_NOW | RTLD_GLOBAL);
    if (!lib) throw IoError(RK_OPENCV_IMGCODECS_SONAME, std::string("cannot load OpenCV's image codecs: ") + ::dlerror());
    Codecs c;
    c.imread = reinterpret_cast<ImReadFn>(::dlsym(lib, kImRead));
    c.imwrite = reinterpret_cast<ImWriteFn>(::dlsym(lib, kImWrite));
    if (!c.imread || !c.imwrite) throw IoError(RK_OPENCV_IMGCODECS_SONAME, "has no cv::imread or cv::imwrite");
    return c;
  }();
  return codecs;
}

}  // namespace

cv::Mat ImRead(const std::string& path, int flags) { return Load().imread(path, flags); }

bool ImWrite(const std::string& path, const cv::Mat& image, const std::vector<int>& params) {
  return Load().imwrite(path, image, params);
}

}  // namespace rk::video

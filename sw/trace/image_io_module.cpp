#include "trace/image_io_module.h"

#include <dlfcn.h>

#include <stdexcept>

namespace kdrt::image_io {

const Module& Get() {
  static const Module* const module = [] {
    void* handle = dlopen(KDRT_IMAGE_IO_MODULE, RTLD_LAZY | RTLD_LOCAL);
    if (handle == nullptr) {
      throw std::runtime_error(std::string("cannot load the image library ") + KDRT_IMAGE_IO_MODULE + ": " +
                               dlerror());
    }
    using Entry = const Module* (*)();
    const auto entry = reinterpret_cast<Entry>(dlsym(handle, "kdrt_image_io_module"));
    const Module* m = entry != nullptr ? entry() : nullptr;
    if (m == nullptr || m->version != kModuleVersion) {
      throw std::runtime_error(std::string("the image library ") + KDRT_IMAGE_IO_MODULE +
                               " is not this build's (rebuild kdrt)");
    }
    return m;
  }();
  return *module;
}

}  // namespace kdrt::image_io

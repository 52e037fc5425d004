#include "driver_pinning.hpp"

#ifdef LUXEL_SANITIZE
#include <dlfcn.h>
#include <link.h>

#include <string>
#include <vector>
#endif

namespace luxel::detail {

#ifdef LUXEL_SANITIZE
namespace {

bool is_gl_driver(const std::string& path) {
    for (const char* marker : {"/dri/", "libEGL_mesa", "libGLX_mesa", "libgallium", "libLLVM",
                               "libglapi", "libOSMesa", "libGLdispatch", "libnvidia"}) {
        if (path.find(marker) != std::string::npos) {
            return true;
        }
    }
    return false;
}

}  // namespace

void pin_gl_driver_modules() {
    std::vector<std::string> drivers;
    dl_iterate_phdr(
        [](dl_phdr_info* info, std::size_t, void* out) {
            if (info->dlpi_name != nullptr && is_gl_driver(info->dlpi_name)) {
                static_cast<std::vector<std::string>*>(out)->emplace_back(info->dlpi_name);
            }
            return 0;
        },
        &drivers);
    for (const auto& path : drivers) {
        // RTLD_NOLOAD: only modules already mapped; RTLD_NODELETE: never unmap them. The handle
        // is deliberately kept for the life of the process.
        (void)dlopen(path.c_str(), RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
    }
}
#else
void pin_gl_driver_modules() {}
#endif

}  // namespace luxel::detail

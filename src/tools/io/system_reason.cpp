#include "sphys/tools/system_reason.h"

#include <system_error>

namespace sphys::tools {

std::string system_reason(int error_number) {
  // strerror's text, without strerror's shared buffer.
  return std::generic_category().message(error_number);
}

}  // namespace sphys::tools

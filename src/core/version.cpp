#include "exemplar/version.hpp"

namespace exemplar {

std::string_view version() {
    return EXEMPLAR_VERSION;
}

}  // namespace exemplar

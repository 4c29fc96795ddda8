#include "mtacc/workflows/option_schemas.hpp"

#include "mtacc/workflows/identification.hpp"

namespace mtacc {

const std::map<std::string, const OptionSchema*>& workflowOptionSchemas() {
  static const std::map<std::string, const OptionSchema*> schemas{{"identify", &identificationSchema()},
                                                                   {"observability", &observabilitySchema()}};
  return schemas;
}

}  // namespace mtacc

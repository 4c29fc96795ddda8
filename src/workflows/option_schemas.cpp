#include "mtacc/workflows/option_schemas.hpp"

#include "mtacc/workflows/budget.hpp"
#include "mtacc/workflows/identification.hpp"
#include "mtacc/workflows/thermal_drift.hpp"

namespace mtacc {

const std::map<std::string, const OptionSchema*>& workflowOptionSchemas() {
  static const std::map<std::string, const OptionSchema*> schemas{
      {"budget", &budgetSchema()}, {"drift", &driftTestSchema()}, {"identify", &identificationSchema()}, {"observability", &observabilitySchema()}};
  return schemas;
}

}  // namespace mtacc

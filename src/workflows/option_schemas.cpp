#include "mtacc/workflows/option_schemas.hpp"

#include "mtacc/workflows/artefacts.hpp"
#include "mtacc/workflows/budget.hpp"
#include "mtacc/workflows/check.hpp"
#include "mtacc/workflows/compensate_options.hpp"
#include "mtacc/workflows/component_fit.hpp"
#include "mtacc/workflows/cone_study.hpp"
#include "mtacc/workflows/cubic_identification.hpp"
#include "mtacc/workflows/cubic_test.hpp"
#include "mtacc/workflows/direct_procedures.hpp"
#include "mtacc/workflows/dynamics_options.hpp"
#include "mtacc/workflows/identification.hpp"
#include "mtacc/workflows/kinematics_options.hpp"
#include "mtacc/workflows/measurement_runs.hpp"
#include "mtacc/workflows/multitasking_identification.hpp"
#include "mtacc/workflows/plates.hpp"
#include "mtacc/workflows/positioning.hpp"
#include "mtacc/workflows/measurement_design.hpp"
#include "mtacc/workflows/rotary_axis_tests.hpp"
#include "mtacc/workflows/acceptance.hpp"
#include "mtacc/workflows/program_deviation.hpp"
#include "mtacc/workflows/recorded_decomposition.hpp"
#include "mtacc/workflows/report_paths.hpp"
#include "mtacc/workflows/simulation_options.hpp"
#include "mtacc/workflows/stiffness.hpp"
#include "mtacc/workflows/thermal_drift.hpp"
#include "mtacc/workflows/virtual_motion.hpp"

namespace mtacc {

const std::map<std::string, const OptionSchema*>& workflowOptionSchemas() {
  static const std::map<std::string, const OptionSchema*> schemas{
      {"budget", &budgetSchema()},
      {"check", &checkSchema()},
      {"compensate", &compensateSchema()},
      {"cone", &coneSchema()},
      {"cubic", &cubicTestSchema()},
      {"cubic-identify", &cubicIdentificationSchema()},
      {"decompose", &decompositionSchema()},
      {"deviation", &programDeviationSchema()},
      {"drift", &driftTestSchema()},
      {"errors", &errorsSchema()},
      {"fk", &forwardSchema()},
      {"ik", &inverseSchema()},
      {"dynamics accel", &structureAccelerationSchema()},
      {"dynamics frf", &structureFrfSchema()},
      {"dynamics map", &structureMapSchema()},
      {"dynamics modes", &structureModesSchema()},
      {"evaluate", &evaluationSchema()},
      {"fit", &componentFitSchema()},
      {"identify", &identificationSchema()},
      {"multitasking", &multitaskingSchema()},
      {"observability", &observabilitySchema()},
      {"plate", &plateComparisonSchema()},
      {"artefact", &artefactEvaluationSchema()},
      {"plate-identify", &plateIdentificationSchema()},
      {"positioning", &positioningSchema()},
      {"rotary-tests", &rotaryTestsSchema()},
      {"acceptance", &acceptanceSchema()},
      {"design", &measurementDesignSchema()},
      {"report", &reportSchema()},
      {"sensitivity", &sensitivitySchema()},
      {"simulate ballbar", &ballbarSimulationSchema()},
      {"simulate component", &componentSimulationSchema()},
      {"simulate motion", &motionSimulationSchema()},
      {"simulate plan", &planSimulationSchema()},
      {"simulate plate", &plateSimulationSchema()},
      {"simulate artefact", &artefactSimulationSchema()},
      {"simulate rtest", &rtestSimulationSchema()},
      {"squareness", &squarenessSchema()},
      {"stiffness", &stiffnessSchema()},
      {"yry", &yrySchema()}};
  return schemas;
}

}  // namespace mtacc

#pragma once
// freeturn as a library: a job read from YAML, run end to end, its report and files.
// The modules' own headers (freeturn/<module>/…) give the parts: surfaces, NURBS, spiral
// planning, compensation, machines, posts (docs/conventions.md, "Layout").

#include "freeturn/core/error.hpp"
#include "freeturn/core/thread_limits.hpp"
#include "freeturn/core/version.hpp"
#include "freeturn/job/job.hpp"
#include "freeturn/job/yaml_limits.hpp"
#include "freeturn/pipeline/installed_posts.hpp"
#include "freeturn/pipeline/run_pipeline.hpp"
#include "freeturn/pipeline/run_report.hpp"
#include "freeturn/report/cl_file.hpp"
#include "freeturn/report/report_files.hpp"
#include "freeturn/report/run_job.hpp"

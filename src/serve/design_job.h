#pragma once
// A lobe-designer job: `specula design` with capped budgets on one core (POST /api/design;
// docs/serve.md), polled for its phase and the front so far.
#include <memory>
#include <string_view>

#include "jobs.h"
#include "specula/serve/api.h"

namespace specula::serve {

/// The job a POST /api/design body asks for, validated (InvalidField naming a bad field) as
/// design::validate validates, its deadline its time budget + Limits::design_grace_seconds.
std::shared_ptr<Job> design_job(std::string_view body, const Limits& limits);

}  // namespace specula::serve

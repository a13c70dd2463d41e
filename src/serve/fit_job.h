#pragma once
// A symbolic-regression job: `specula fit` on columns of data or on a lobe model's exact
// normalization k(n), with capped budgets (POST /api/fit; docs/serve.md).
#include <memory>
#include <string_view>

#include "jobs.h"
#include "specula/serve/api.h"

namespace specula::serve {

/// The job a POST /api/fit body asks for, validated (InvalidField naming a bad field), its
/// deadline its time budget + Limits::fit_grace_seconds.
std::shared_ptr<Job> fit_job(std::string_view body, const Limits& limits);

}  // namespace specula::serve

#pragma once
// The lab's lit object under an environment (BRDF Explorer's image-based-lighting view): a model
// on a mesh (the unit sphere, the bundled knot or an upload) lit by a probe (the white furnace,
// the bundled sky or an upload), rendered progressively by the CPU renderer on one core (POST
// /api/environment; docs/serve.md). Polling gives the image so far as a PNG with its sample count.
#include <memory>
#include <string_view>

#include "jobs.h"
#include "specula/serve/api.h"
#include "uploads.h"

namespace specula::serve {

/// The job a POST /api/environment body asks for, validated (InvalidField naming a bad field),
/// its deadline Limits::environment_seconds.
std::shared_ptr<Job> environment_job(std::string_view body, const Limits& limits, const Uploads& uploads);

/// The samples of pass `pass` (0, 1, …) of a render toward `target` samples per pixel that has
/// `done` of them: 1, 2, 4, … up to 16 per pass, the last one what is left. The page sees a
/// first image at once and the later passes cost about the same each.
int pass_samples(int pass, int done, int target);

}  // namespace specula::serve

// The parameter block of core/include/habuffer/shared/ha_params.h as the GL
// path uploads it: GlParams, the core's ParamBlock (habuffer/technique_params.h,
// whose std140 layout is checked there), one struct for both paths.
#pragma once

#include "habuffer/gl/gl_technique.h"

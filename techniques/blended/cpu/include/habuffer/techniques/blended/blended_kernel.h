/// @file
/// Forwarding header, kept for one release: the kernel is an implementation
/// detail of the technique and lives in detail/ (issue 47). Include the
/// technique's container header, or habuffer/techniques/blended/detail/blended_kernel.h.
#pragma once

#include "habuffer/techniques/blended/detail/blended_kernel.h"

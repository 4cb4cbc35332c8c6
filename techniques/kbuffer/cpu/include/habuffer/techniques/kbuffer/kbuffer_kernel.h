/// @file
/// Forwarding header, kept for one release: the kernel is an implementation
/// detail of the technique and lives in detail/ (issue 47). Include the
/// technique's container header, or habuffer/techniques/kbuffer/detail/kbuffer_kernel.h.
#pragma once

#include "habuffer/techniques/kbuffer/detail/kbuffer_kernel.h"

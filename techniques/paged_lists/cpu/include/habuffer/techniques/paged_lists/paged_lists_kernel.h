/// @file
/// Forwarding header, kept for one release: the kernel is an implementation
/// detail of the technique and lives in detail/ (issue 47). Include the
/// technique's container header, or habuffer/techniques/paged_lists/detail/paged_lists_kernel.h.
#pragma once

#include "habuffer/techniques/paged_lists/detail/paged_lists_kernel.h"

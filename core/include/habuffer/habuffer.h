/// @file
/// habuffer's CPU path in one include: fragments and configurations, the
/// HA-buffer and every peer technique behind FragmentBuffer, lossless
/// builds, compositing and the exact reference, memory models and offsets.
/// The kernels (hash_kernel.h, lists_kernel.h, ...) are for code that runs
/// the shared algorithm itself and are included on their own.
#pragma once

#include "habuffer/techniques/blended/blended_image.h"
#include "habuffer/buffer_config.h"
#include "habuffer/build_report.h"
#include "habuffer/extent.h"
#include "habuffer/techniques/arrays/fixed_arrays.h"
#include "habuffer/fragment.h"
#include "habuffer/fragment_buffer.h"
#include "habuffer/techniques/ha/ha_buffer.h"
#include "habuffer/techniques/kbuffer/kbuffer.h"
#include "habuffer/techniques/linked_lists/linked_lists.h"
#include "habuffer/techniques/paged_lists/paged_lists.h"
#include "habuffer/lossless_build.h"
#include "habuffer/technique_frames.h"
#include "habuffer/max_age_table.h"
#include "habuffer/memory_model.h"
#include "habuffer/offset_sequence.h"
#include "habuffer/parallel.h"
#include "habuffer/record_layout.h"
#include "habuffer/reference_compositor.h"
#include "habuffer/resize_policy.h"
#include "habuffer/technique.h"
#include "habuffer/technique_params.h"
#include "habuffer/transmittance.h"
#include "habuffer/spatial/spatial_hash.h"

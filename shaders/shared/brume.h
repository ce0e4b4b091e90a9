// Everything the CPU and the GPU share, in include order.
#ifndef BRUME_SHARED_H
#define BRUME_SHARED_H
#include "common.h"
#include "specialization.h"
#include "types.h"
#include "froxel.h"
#include "media.h"
#include "vdb.h"
#include "density_texture.h"
#include "lighting.h"
#include "glow.h"
#include "integrate.h"
#include "temporal.h"
#include "distant.h"
#include "shadows.h"
#include "shadow_volume.h"
#include "vdb_shadow.h"
#include "clusters.h"
#include "sun_shadow.h"
#include "local_shadow.h"
#include "tonemap.h"
#include "debug_view.h"
#endif

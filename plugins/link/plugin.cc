// SPDX-License-Identifier: GPL-3.0-or-later
#include "link.h"

UNIMOUSE_EXPORT_PLUGIN(unimouse::link::Link)

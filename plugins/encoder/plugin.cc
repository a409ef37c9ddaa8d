// SPDX-License-Identifier: GPL-3.0-or-later
#include "encoder.h"

UNIMOUSE_EXPORT_PLUGIN(unimouse::plugins::Encoder)

// SPDX-License-Identifier: GPL-3.0-or-later
#include "dc_motor.h"

UNIMOUSE_EXPORT_PLUGIN(unimouse::plugins::DcMotor)

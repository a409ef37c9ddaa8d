// SPDX-License-Identifier: MIT
// The UnimouseSim library: `#include <UnimouseSim.h>` brings in all of it.
#ifndef UNIMOUSE_SIM_H_
#define UNIMOUSE_SIM_H_

#include "Devices.h"
#include "FFSolver.h"
#include "Maze.h"
#include "PathManager.h"
#include "PoseEstimator.h"
#include "RobotConstructionSpecification.h"
#include "SimulationActuators.h"
#include "SimulationRobot.h"
#include "SimulationSensors.h"
#include "unimouse_protocol.h"

#endif  // UNIMOUSE_SIM_H_

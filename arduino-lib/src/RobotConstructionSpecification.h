// SPDX-License-Identifier: MIT
// The robot's dimensions that firmware computes with (dissertation table 3.12). Table 3.12 prints
// 0.032 m as the wheel radius; the original library and robot model both use 0.016 m, so 0.032 m
// is the diameter. Counts per wheel turn: 12 per motor turn times the 29.86:1 gearbox.
#ifndef UNIMOUSE_SIM_ROBOT_CONSTRUCTION_SPECIFICATION_H_
#define UNIMOUSE_SIM_ROBOT_CONSTRUCTION_SPECIFICATION_H_

struct RobotConstructionSpecification {
  float leftWheelRadius = 0.016f;    // m
  float rightWheelRadius = 0.016f;   // m
  float wheelBaseDistance = 0.096f;  // m, between the wheels' contact points (2d in eq. 3.26)
  float leftWheelCPR = 358.32f;      // encoder counts per wheel turn
  float rightWheelCPR = 358.32f;
};

#endif  // UNIMOUSE_SIM_ROBOT_CONSTRUCTION_SPECIFICATION_H_

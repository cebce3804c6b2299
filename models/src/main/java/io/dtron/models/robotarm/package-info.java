/**
 * The robot arm of the control sample ({@code robot-arm.xta}, {@code dtron control}): the arm as a plant on the
 * JGroups bus, in its own process ({@link io.dtron.models.robotarm.RobotArmPlant}).
 */
package io.dtron.models.robotarm;

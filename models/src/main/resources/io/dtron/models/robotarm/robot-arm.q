// What every version of the robot arm's controller must guarantee: dtron verify robot-arm.xta --queries robot-arm.q,
// and what dtron control --reload-from checks a new version with when it has no .q of its own.
A[] not deadlock
A[] (Arm.Moving imply Arm.y <= 5)
A[] not Controller.Safe
E<> Controller.Holding

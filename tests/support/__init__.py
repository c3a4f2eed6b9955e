"""What the tests share: shapes and solids, independent measures, simulators, the robot corpus."""

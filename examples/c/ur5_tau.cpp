// The UR5's joint torques from C++, through the C that `rne emit --lang c ur5` writes
// (README.md in this directory: how to build and run it).
#include <cstdio>

#include "ur5.h"

int main() {
    const double q[UR5_NQ] = {0.1, -1.2, 1.5, -0.4, 0.8, 0.3};
    const double qd[UR5_NV] = {0.5, -0.3, 0.2, 1.0, -0.7, 0.4};
    const double qdd[UR5_NV] = {1.0, 0.5, -2.0, 0.3, 0.0, -1.5};
    double tau[UR5_NV];
    ur5_inverse_dynamics(q, qd, qdd, tau);
    for (int i = 0; i < UR5_NV; i++) {
        std::printf("%-20s %.17g\n", ur5_joint_names[i], tau[i]);
    }
    return 0;
}

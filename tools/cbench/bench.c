/* Time per call of rne's C kernels of one robot (tools/cbench/run.sh builds and runs it).
 *
 *   cc -O2 -DROBOT=ur5 -DUPPER=UR5 -DROBOT_H='"ur5.h"' -I DIR tools/cbench/bench.c DIR/ur5.c -o bench
 *
 * with DIR/ur5.h and DIR/ur5.c from `rne emit --lang c ur5 --outputs inverse_dynamics,
 * mass_matrix,forward_dynamics,inverse_dynamics_derivatives,forward_dynamics_derivatives
 * --out DIR`. The states, the loop and the figure are those of the Rust side (src/main.rs):
 * 1024 states drawn by the same generator, each kernel called on 128 consecutive states per
 * run, runs repeated for a second; the figure is the fastest run's time per call, in
 * nanoseconds. */
#define _POSIX_C_SOURCE 199309L
#define CAT(a, b) a##b
#define NAME(robot, kernel) CAT(robot, kernel)

#include ROBOT_H
#include <stdint.h>
#include <stdio.h>
#include <time.h>

#define NQ NAME(UPPER, _NQ)
#define NV NAME(UPPER, _NV)
#define STATES 1024

static double q[STATES][NQ], qd[STATES][NV], qdd[STATES][NV];
static double out[3][NV * NV];
static volatile double sink;

/* The generator of src/main.rs: xorshift64*, uniform in [-1, 1). */
static uint64_t state = 0x9E3779B97F4A7C15u;
static double uniform(void) {
    state ^= state >> 12;
    state ^= state << 25;
    state ^= state >> 27;
    return (double)((state * 0x2545F4914F6CDD1Du) >> 11) / 4503599627370496.0 - 1.0;
}

static double now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* The best time per call over runs of RUN calls (on consecutive states), run for at least a
 * second: on a shared machine, the shortest run is the one no other process interrupted. */
#define RUN 128
#define TIME(label, call)                                                                   \
    do {                                                                                    \
        double best = 1e300, total = 0.0;                                                   \
        int run;                                                                            \
        for (run = 0; total < 1.0 || run < 50; run++) {                                     \
            const double start = now();                                                     \
            double elapsed;                                                                 \
            int s;                                                                          \
            for (s = (run * RUN) % STATES; s < (run * RUN) % STATES + RUN; s++) {           \
                call;                                                                       \
                sink = out[0][0];                                                           \
            }                                                                               \
            elapsed = now() - start;                                                        \
            total += elapsed;                                                               \
            if (elapsed < best) best = elapsed;                                             \
        }                                                                                   \
        printf("%-32s %9.1f ns\n", label, best / RUN * 1e9);                                \
    } while (0)

int main(void) {
    int s, i;
    for (s = 0; s < STATES; s++) {
        for (i = 0; i < NQ; i++) q[s][i] = 3.0 * uniform();
        for (i = 0; i < NV; i++) qd[s][i] = 2.0 * uniform();
        for (i = 0; i < NV; i++) qdd[s][i] = 5.0 * uniform();
    }
    TIME("inverse_dynamics", NAME(ROBOT, _inverse_dynamics)(q[s], qd[s], qdd[s], out[0]));
    TIME("mass_matrix", NAME(ROBOT, _mass_matrix)(q[s], out[0]));
    TIME("forward_dynamics", NAME(ROBOT, _forward_dynamics)(q[s], qd[s], qdd[s], out[0]));
    TIME("inverse_dynamics_derivatives",
         NAME(ROBOT, _inverse_dynamics_derivatives)(q[s], qd[s], qdd[s], out[0], out[1]));
    TIME("forward_dynamics_derivatives",
         NAME(ROBOT, _forward_dynamics_derivatives)(q[s], qd[s], qdd[s], out[0], out[1], out[2]));
    return 0;
}

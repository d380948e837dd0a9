// CPU time of this process and of the whole machine, for the benchmarks that wait for an idle
// machine and drop the passes other processes disturbed.
#pragma once

#include <unistd.h>

#include <ctime>
#include <fstream>
#include <string>

namespace luz::bench {

/// CPU seconds used by this process (all threads).
inline double cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// CPU seconds spent by the whole machine (all processes, /proc/stat), or −1 if unknown.
inline double machine_busy_seconds() {
    std::ifstream in("/proc/stat");
    std::string cpu;
    unsigned long long user, nice, system, idle, iowait, irq, softirq, steal;
    if (!(in >> cpu >> user >> nice >> system >> idle >> iowait >> irq >> softirq >> steal))
        return -1;
    const double hz = static_cast<double>(sysconf(_SC_CLK_TCK));
    return static_cast<double>(user + nice + system + irq + softirq + steal) / hz;
}

}  // namespace luz::bench

// A hostile submission, for the grader's tests (graded in containers only): a fork bomb that
// never starts a ROS node. Merely present it does nothing.
#include <unistd.h>

int main()
{
    while (true) {
        fork();
    }
}

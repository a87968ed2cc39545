// A hostile submission, for the grader's tests (graded in containers only): every executable of the
// package is this program. It never starts a ROS node; it tries to write outside its folder and to
// open a connection, forks what it can, then prints without end. Merely present it does nothing.
#include <arpa/inet.h>
#include <cstdio>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

int main()
{
    const char* targets[] = {"/submission/hostile_was_here", "/hostile_was_here", "../../../hostile_was_here"};
    for (const char* target : targets) {
        FILE* file = fopen(target, "w");
        if (file) {
            fputs("hostile\n", file);
            fclose(file);
        }
    }
    int sock = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address = {};
    address.sin_family = AF_INET;
    address.sin_port = htons(80);
    inet_pton(AF_INET, "192.0.2.1", &address.sin_addr);  // TEST-NET-1: never routed
    connect(sock, reinterpret_cast<sockaddr*>(&address), sizeof(address));
    for (int i = 0; i < 64; ++i) {
        if (fork() == 0) {
            break;
        }
    }
    while (true) {
        puts("spam spam spam spam spam spam spam spam spam spam spam spam spam spam spam spam");
    }
}

/*
 * Loaded with LD_PRELOAD, keeps the TCP servers of ROS processes on loopback.
 *
 * Why: with ROS_HOSTNAME=localhost a node advertises only loopback URIs, and rospy, rosmaster and
 * roscpp's TCPROS bind 127.0.0.1 accordingly. roscpp's XML-RPC server (xmlrpcpp: every C++ node,
 * rosout, robot_state_publisher) binds INADDR_ANY regardless, so anyone on the network can reach it
 * and, through it, ask the node to connect to topics or shut down. This library rewrites that one
 * case: a bind() of a TCP socket to the wildcard address becomes a bind to the loopback address of
 * the same family.
 *
 * It acts only when the address the node advertises is a loopback address: ROS_HOSTNAME if set,
 * else ROS_IP (the precedence roscpp and rospy use). With ROS_IP or ROS_HOSTNAME set to a real
 * address (two machines) every bind() is passed through untouched. Only stream sockets are rewritten
 * so that UDP clients that bind the wildcard before talking to other hosts (DNS tools, for instance)
 * keep working in a shell that preloads this library.
 */
#define _GNU_SOURCE
#include <arpa/inet.h>
#include <dlfcn.h>
#include <errno.h>
#include <netinet/in.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/socket.h>

typedef int (*bind_function)(int, const struct sockaddr *, socklen_t);

static bind_function real_bind;
static int advertises_loopback;
/* Where a wildcard IPv4 bind goes: the advertised address itself when it is a 127.x literal (peers
 * connect to exactly that address, as rospy binds it), else 127.0.0.1. */
static struct in_addr ipv4_loopback;

/* True for the names and addresses ROS treats as "this machine only": localhost, 127.0.0.0/8, ::1. */
static int names_loopback(const char *address)
{
    struct in_addr ipv4;
    struct in6_addr ipv6;

    if (strcasecmp(address, "localhost") == 0)
        return 1;
    if (inet_pton(AF_INET, address, &ipv4) == 1)
        return (ntohl(ipv4.s_addr) >> 24) == 127;
    if (inet_pton(AF_INET6, address, &ipv6) == 1)
        return IN6_IS_ADDR_LOOPBACK(&ipv6);
    return 0;
}

/* The address a ROS node advertises: ROS_HOSTNAME wins over ROS_IP, as in roscpp and rospy. */
static const char *advertised_address(void)
{
    const char *hostname = getenv("ROS_HOSTNAME");
    if (hostname && *hostname)
        return hostname;
    return getenv("ROS_IP");
}

/* Runs when the library is loaded, before main(): the environment a process starts with decides,
 * so every bind() of the process follows the same rule. bind() also calls it if another library's
 * constructor binds before this one ran (constructors of preloaded libraries run late). */
__attribute__((constructor)) static void read_environment(void)
{
    const char *address = advertised_address();
    advertises_loopback = address && *address && names_loopback(address);
    if (!advertises_loopback || inet_pton(AF_INET, address, &ipv4_loopback) != 1)
        ipv4_loopback.s_addr = htonl(INADDR_LOOPBACK);
    real_bind = (bind_function)dlsym(RTLD_NEXT, "bind");
}

static int is_stream_socket(int fd)
{
    int type = 0;
    socklen_t length = sizeof type;
    return getsockopt(fd, SOL_SOCKET, SO_TYPE, &type, &length) == 0 && type == SOCK_STREAM;
}

int bind(int fd, const struct sockaddr *address, socklen_t length)
{
    if (!real_bind)
        read_environment();
    if (!real_bind) {
        errno = ENOSYS;
        return -1;
    }
    if (!advertises_loopback || !address || !is_stream_socket(fd))
        return real_bind(fd, address, length);

    if (address->sa_family == AF_INET && length >= sizeof(struct sockaddr_in)) {
        struct sockaddr_in loopback;
        memcpy(&loopback, address, sizeof loopback);
        if (loopback.sin_addr.s_addr == htonl(INADDR_ANY)) {
            loopback.sin_addr = ipv4_loopback;
            return real_bind(fd, (const struct sockaddr *)&loopback, sizeof loopback);
        }
    } else if (address->sa_family == AF_INET6 && length >= sizeof(struct sockaddr_in6)) {
        struct sockaddr_in6 loopback;
        memcpy(&loopback, address, sizeof loopback);
        if (IN6_IS_ADDR_UNSPECIFIED(&loopback.sin6_addr)) {
            loopback.sin6_addr = in6addr_loopback;
            return real_bind(fd, (const struct sockaddr *)&loopback, sizeof loopback);
        }
    }
    return real_bind(fd, address, length);
}

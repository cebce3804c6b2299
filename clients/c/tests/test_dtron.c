/*
 * libdtron against a nats-server the test starts (JetStream, a free loopback port, a temporary store): members see
 * one order and each other; the handshake, clock offset and acknowledgements against a tester played with raw
 * NATS; bad input rejected and counted. Exit 77 (skipped) without nats-server, unless DTRON_REQUIRE_NATS=1.
 */
#define _POSIX_C_SOURCE 200809L
#include <dtron.h>
#include <nats/nats.h>
#include <netinet/in.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "Sync.pb-c.h"

#define CHECK(condition)                                                                     \
    do {                                                                                     \
        if (!(condition)) {                                                                  \
            fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #condition);   \
            failures++;                                                                      \
        }                                                                                    \
    } while (0)

static int failures;
static char url[64];
static char store[64] = "/tmp/dtron-c-test-XXXXXX";
static pid_t server;

static void pause_ms(long ms) {
    struct timespec step = {ms / 1000, (ms % 1000) * 1000000L};
    nanosleep(&step, NULL);
}

/* Waits up to 10 s until condition holds. */
#define UNTIL(condition)                                                     \
    do {                                                                     \
        for (int waited = 0; !(condition) && waited < 1000; waited++) {      \
            pause_ms(10);                                                    \
        }                                                                    \
    } while (0)

static const char *nats_server(void) {
    static const char *const candidates[] = {"/usr/bin/nats-server", "/usr/sbin/nats-server",
                                             "/usr/local/bin/nats-server"};
    for (size_t i = 0; i < sizeof candidates / sizeof *candidates; i++) {
        if (access(candidates[i], X_OK) == 0) {
            return candidates[i];
        }
    }
    return NULL;
}

static int start_server(void) {
    const char *binary = nats_server();
    if (binary == NULL) {
        const char *required = getenv("DTRON_REQUIRE_NATS");
        fprintf(stderr, "nats-server is not installed%s\n", required && strcmp(required, "1") == 0
                                                              ? ", and DTRON_REQUIRE_NATS=1 requires it" : ": skipped");
        exit(required && strcmp(required, "1") == 0 ? 1 : 77);
    }
    int probe = socket(AF_INET, SOCK_STREAM, 0);
    struct sockaddr_in address = {.sin_family = AF_INET, .sin_addr.s_addr = htonl(INADDR_LOOPBACK)};
    socklen_t length = sizeof address;
    bind(probe, (struct sockaddr *)&address, sizeof address);
    getsockname(probe, (struct sockaddr *)&address, &length);
    int port = ntohs(address.sin_port);
    close(probe);
    if (mkdtemp(store) == NULL) {
        return -1;
    }
    char port_text[16];
    snprintf(port_text, sizeof port_text, "%d", port);
    snprintf(url, sizeof url, "nats://127.0.0.1:%d", port);
    server = fork();
    if (server == 0) {
        freopen("/dev/null", "w", stderr);
        execl(binary, binary, "-a", "127.0.0.1", "-p", port_text, "-js", "-sd", store, (char *)NULL);
        _exit(127);
    }
    for (int i = 0; i < 300; i++) { /* until it accepts connections */
        natsConnection *nc = NULL;
        if (natsConnection_ConnectTo(&nc, url) == NATS_OK) {
            natsConnection_Destroy(nc);
            return 0;
        }
        pause_ms(20);
    }
    return -1;
}

static void stop_server(void) {
    char command[128];
    kill(server, SIGTERM);
    waitpid(server, NULL, 0);
    snprintf(command, sizeof command, "rm -rf %s", store);
    if (system(command) != 0) {
        fprintf(stderr, "cannot remove %s\n", store);
    }
}

/* ---- one order, membership ---- */

typedef struct {
    pthread_mutex_t lock;
    char seen[400][48];
    int count;
} record;

static void recorded(dtron_bus *bus, const dtron_message *message, void *closure) {
    record *r = closure;
    (void)bus;
    pthread_mutex_lock(&r->lock);
    if (r->count < 400) {
        snprintf(r->seen[r->count++], 48, "%s:%d", message->sender, message->vars[0].value);
    }
    pthread_mutex_unlock(&r->lock);
}

static int count_of(record *r) {
    pthread_mutex_lock(&r->lock);
    int count = r->count;
    pthread_mutex_unlock(&r->lock);
    return count;
}

static const char *const ORDER_VARS[] = {"n"};

static void *burst(void *closure) {
    for (int n = 1; n <= 100; n++) {
        dtron_var var = {"n", n};
        dtron_send(closure, "order", &var, 1, 0);
    }
    return NULL;
}

static void test_order_and_membership(void) {
    dtron_options a_options = {.servers = url, .bus = "order", .member = "a"};
    dtron_options b_options = {.servers = url, .bus = "order", .member = "b"};
    dtron_bus *a = NULL, *b = NULL;
    static record ra = {.lock = PTHREAD_MUTEX_INITIALIZER}, rb = {.lock = PTHREAD_MUTEX_INITIALIZER};
    char err[256];
    CHECK(dtron_connect(&a_options, &a, err, sizeof err) == DTRON_OK);
    CHECK(dtron_connect(&b_options, &b, err, sizeof err) == DTRON_OK);
    if (a == NULL || b == NULL) {
        fprintf(stderr, "connect: %s\n", err);
        exit(1);
    }
    CHECK(dtron_listen(a, "order", ORDER_VARS, 1, recorded, &ra, 1) == DTRON_OK);
    CHECK(dtron_listen(b, "order", ORDER_VARS, 1, recorded, &rb, 1) == DTRON_OK);
    CHECK(dtron_declare_output(a, "order", ORDER_VARS, 1) == DTRON_OK);
    CHECK(dtron_declare_output(b, "order", ORDER_VARS, 1) == DTRON_OK);
    UNTIL(dtron_member_count(a) == 2 && dtron_member_count(b) == 2);
    CHECK(dtron_member_count(a) == 2);
    dtron_var wrong = {"m", 1};
    CHECK(dtron_send(a, "order", &wrong, 1, 0) == DTRON_ERR_ARGUMENT);
    CHECK(dtron_send(a, "dtron_ack", NULL, 0, 0) == DTRON_ERR_ARGUMENT);
    pthread_t ta, tb;
    pthread_create(&ta, NULL, burst, a);
    pthread_create(&tb, NULL, burst, b);
    pthread_join(ta, NULL);
    pthread_join(tb, NULL);
    UNTIL(count_of(&ra) == 200 && count_of(&rb) == 200);
    CHECK(count_of(&ra) == 200 && count_of(&rb) == 200);
    int same = 1;
    for (int i = 0; i < 200; i++) {
        same &= strcmp(ra.seen[i], rb.seen[i]) == 0;
    }
    CHECK(same);
    CHECK(dtron_get_stats(a).published == 100 && dtron_get_stats(a).accepted == 200);
    dtron_close(b);
    UNTIL(dtron_member_count(a) == 1);
    CHECK(dtron_member_count(a) == 1);
    dtron_close(a);
}

/* ---- a tester played with raw NATS ---- */

typedef struct {
    natsConnection *nc;
    pthread_mutex_t lock;
    int serve_ok, pings, acks;
    uint64_t acked_sequence;
    char acked_sender[32];
    int64_t ack_offset, ack_error;
    uint64_t sequence;
} fake_tester;

static void tester_publish(fake_tester *t, const char *channel, const char *variable, int value, const char *acked,
                           uint64_t acked_sequence, int64_t event_ns, uint64_t *sequence_out) {
    Dtron__Sync sync = DTRON__SYNC__INIT;
    Dtron__Variable var = DTRON__VARIABLE__INIT;
    Dtron__Variable *vars[] = {&var};
    char subject[128];
    pthread_mutex_lock(&t->lock);
    uint64_t sequence = ++t->sequence;
    pthread_mutex_unlock(&t->lock);
    sync.name = (char *)channel;
    sync.sender = "tester";
    sync.sequence = sequence;
    sync.publish_time_ns = dtron_now_ns() + 50000000LL; /* the tester's clock is 50 ms ahead */
    sync.event_time_ns = event_ns;
    sync.acked_sender = (char *)(acked ? acked : "");
    sync.acked_sequence = acked_sequence;
    if (variable) {
        var.name = (char *)variable;
        var.value = value;
        sync.n_variables = 1;
        sync.variables = vars;
    }
    uint8_t buffer[512];
    size_t length = dtron__sync__pack(&sync, buffer);
    snprintf(subject, sizeof subject, "dtron.hand.c.%s", channel);
    natsMsg *msg = NULL;
    natsMsg_Create(&msg, subject, NULL, (const char *)buffer, (int)length);
    natsMsgHeader_Set(msg, "Dtron-Sender", "tester");
    natsConnection_PublishMsg(t->nc, msg);
    natsMsg_Destroy(msg);
    if (sequence_out) {
        *sequence_out = sequence;
    }
}

static void tester_received(natsConnection *nc, natsSubscription *sub, natsMsg *msg, void *closure) {
    fake_tester *t = closure;
    const char *subject = natsMsg_GetSubject(msg);
    const char *channel = strrchr(subject, '.') + 1;
    Dtron__Sync *sync = dtron__sync__unpack(NULL, (size_t)natsMsg_GetDataLength(msg),
                                            (const uint8_t *)natsMsg_GetData(msg));
    (void)nc;
    (void)sub;
    if (sync != NULL && strcmp(sync->sender, "tester") != 0) {
        if (strcmp(channel, "dtron_serve") == 0) {
            pthread_mutex_lock(&t->lock);
            t->serve_ok |= sync->n_receives == 1 && strcmp(sync->receives[0], "reset") == 0 && sync->n_sends == 1
                           && strcmp(sync->sends[0], "tick") == 0;
            pthread_mutex_unlock(&t->lock);
        } else if (strcmp(channel, "dtron_ping") == 0) {
            pthread_mutex_lock(&t->lock);
            t->pings++;
            pthread_mutex_unlock(&t->lock);
            tester_publish(t, "dtron_pong", NULL, 0, sync->sender, sync->sequence, dtron_now_ns() + 50000000LL, NULL);
        } else if (strcmp(channel, "dtron_ack") == 0) {
            pthread_mutex_lock(&t->lock);
            t->acks++;
            t->acked_sequence = sync->acked_sequence;
            snprintf(t->acked_sender, sizeof t->acked_sender, "%s", sync->acked_sender);
            t->ack_offset = sync->clock_offset_ns;
            t->ack_error = sync->clock_error_ns;
            pthread_mutex_unlock(&t->lock);
        }
    }
    if (sync) {
        dtron__sync__free_unpacked(sync, NULL);
    }
    natsMsg_Destroy(msg);
}

static int resets;

static void on_reset(dtron_bus *bus, const dtron_message *message, void *closure) {
    (void)bus;
    (void)closure;
    resets += strcmp(message->sender, "tester") == 0;
}

static int field(fake_tester *t, int *value) {
    pthread_mutex_lock(&t->lock);
    int copy = *value;
    pthread_mutex_unlock(&t->lock);
    return copy;
}

static void test_handshake_clock_and_acknowledgements(void) {
    static const char *const tick_vars[] = {"seq"};
    static fake_tester t = {.lock = PTHREAD_MUTEX_INITIALIZER};
    natsSubscription *sub = NULL;
    dtron_options options = {.servers = url, .bus = "hand", .member = "adapter"};
    dtron_bus *adapter = NULL;
    char err[256];
    CHECK(natsConnection_ConnectTo(&t.nc, url) == NATS_OK);
    CHECK(natsConnection_Subscribe(&sub, t.nc, "dtron.hand.c.>", tester_received, &t) == NATS_OK);
    natsConnection_Flush(t.nc);
    CHECK(dtron_connect(&options, &adapter, err, sizeof err) == DTRON_OK);
    if (adapter == NULL) {
        fprintf(stderr, "connect: %s\n", err);
        exit(1);
    }
    dtron_declare_output(adapter, "tick", tick_vars, 1);
    CHECK(dtron_listen(adapter, "reset", NULL, 0, on_reset, NULL, 1) == DTRON_OK);
    CHECK(dtron_listen(adapter, "dtron_ping", NULL, 0, on_reset, NULL, 1) == DTRON_ERR_ARGUMENT);
    tester_publish(&t, "dtron_hello", NULL, 0, NULL, 0, 0, NULL);
    UNTIL(field(&t, &t.serve_ok));
    CHECK(field(&t, &t.serve_ok));
    int64_t offset = 0, error = 0;
    UNTIL(field(&t, &t.pings) >= 8 && dtron_clock_offset(adapter, &offset, &error));
    CHECK(dtron_clock_offset(adapter, &offset, &error));
    CHECK(error > 0 && llabs(offset - 50000000LL) <= error);
    tester_publish(&t, "dtron_start", "timeunit", 1000, NULL, 0, 0, NULL);
    UNTIL(dtron_run_running(adapter));
    CHECK(dtron_run_running(adapter));
    CHECK(dtron_run_now_units(adapter) >= 0 && dtron_run_now_units(adapter) < 1000);
    uint64_t reset_sequence = 0;
    tester_publish(&t, "reset", NULL, 0, NULL, 0, 0, &reset_sequence);
    UNTIL(field(&t, &t.acks) == 1);
    CHECK(field(&t, &t.acks) == 1 && resets == 1);
    CHECK(t.acked_sequence == reset_sequence && strcmp(t.acked_sender, "tester") == 0);
    CHECK(t.ack_error > 0 && llabs(t.ack_offset - 50000000LL) <= t.ack_error);
    tester_publish(&t, "dtron_stop", NULL, 0, NULL, 0, 0, NULL);
    UNTIL(!dtron_run_running(adapter));
    CHECK(!dtron_run_running(adapter));

    /* bad input: no Sync, unknown and missing variables, then a good one */
    natsConnection_PublishString(t.nc, "dtron.hand.c.reset", "\xff\x01\x02");
    tester_publish(&t, "reset", "n", 1, NULL, 0, 0, NULL);
    tester_publish(&t, "reset", NULL, 0, NULL, 0, 0, NULL);
    UNTIL(resets == 2);
    dtron_stats stats = dtron_get_stats(adapter);
    CHECK(resets == 2);
    CHECK(stats.malformed == 1 && stats.unknown_variables == 1 && stats.accepted == 2);
    dtron_close(adapter);
    natsSubscription_Destroy(sub);
    natsConnection_Destroy(t.nc);
}

int main(void) {
    if (start_server() != 0) {
        fprintf(stderr, "nats-server did not start\n");
        return 1;
    }
    test_order_and_membership();
    test_handshake_clock_and_acknowledgements();
    stop_server();
    dtron_shutdown();
    if (failures) {
        fprintf(stderr, "%d checks failed\n", failures);
        return 1;
    }
    printf("all checks passed\n");
    return 0;
}

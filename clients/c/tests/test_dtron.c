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

/* A nats-server of the test: its process, its URL and its JetStream store. */
typedef struct {
    pid_t pid;
    char url[64];
    char store[64];
} nats_server_process;

static nats_server_process plain;

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

static int required(void) {
    const char *value = getenv("DTRON_REQUIRE_NATS");
    return value && strcmp(value, "1") == 0;
}

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

/* Whether something accepts TCP connections on 127.0.0.1:port. */
static int listening(int port) {
    int probe = socket(AF_INET, SOCK_STREAM, 0);
    struct sockaddr_in address = {.sin_family = AF_INET, .sin_port = htons(port),
                                  .sin_addr.s_addr = htonl(INADDR_LOOPBACK)};
    int ok = connect(probe, (struct sockaddr *)&address, sizeof address) == 0;
    close(probe);
    return ok;
}

/* Starts nats-server with JetStream on a free loopback port and the extra options (NULL-terminated, at most 8). */
static int start_server(nats_server_process *p, const char *scheme, const char *const *extra) {
    const char *binary = nats_server();
    if (binary == NULL) {
        fprintf(stderr, "nats-server is not installed%s\n", required() ? ", and DTRON_REQUIRE_NATS=1 requires it"
                                                                         : ": skipped");
        exit(required() ? 1 : 77);
    }
    int probe = socket(AF_INET, SOCK_STREAM, 0);
    struct sockaddr_in address = {.sin_family = AF_INET, .sin_addr.s_addr = htonl(INADDR_LOOPBACK)};
    socklen_t length = sizeof address;
    bind(probe, (struct sockaddr *)&address, sizeof address);
    getsockname(probe, (struct sockaddr *)&address, &length);
    int port = ntohs(address.sin_port);
    close(probe);
    snprintf(p->store, sizeof p->store, "/tmp/dtron-c-test-XXXXXX");
    if (mkdtemp(p->store) == NULL) {
        return -1;
    }
    char port_text[16];
    snprintf(port_text, sizeof port_text, "%d", port);
    snprintf(p->url, sizeof p->url, "%s://127.0.0.1:%d", scheme, port);
    const char *argv[20] = {binary, "-a", "127.0.0.1", "-p", port_text, "-js", "-sd", p->store};
    int argc = 8;
    for (int i = 0; extra && extra[i] && argc < 19; i++) {
        argv[argc++] = extra[i];
    }
    argv[argc] = NULL;
    p->pid = fork();
    if (p->pid == 0) {
        freopen("/dev/null", "w", stderr);
        execv(binary, (char *const *)argv);
        _exit(127);
    }
    for (int i = 0; i < 300; i++) { /* until it accepts connections */
        if (listening(port)) {
            pause_ms(100); /* and JetStream is up */
            return 0;
        }
        pause_ms(20);
    }
    return -1;
}

static void stop_server(nats_server_process *p) {
    char command[128];
    kill(p->pid, SIGTERM);
    waitpid(p->pid, NULL, 0);
    snprintf(command, sizeof command, "rm -rf %s", p->store);
    if (system(command) != 0) {
        fprintf(stderr, "cannot remove %s\n", p->store);
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

/* ---- authentication: a token; TLS trusting a given authority ---- */

static void test_token(void) {
    static const char *const extra[] = {"--auth", "t0ken-s3cret", NULL};
    nats_server_process p;
    CHECK(start_server(&p, "nats", extra) == 0);
    char err[256] = "";
    dtron_bus *bus = NULL;
    dtron_options none = {.servers = p.url, .bus = "auth", .member = "m"};
    CHECK(dtron_connect(&none, &bus, err, sizeof err) == DTRON_ERR_BUS && bus == NULL);
    CHECK(strstr(err, "cannot connect to NATS servers") != NULL);
    dtron_options wrong = {.servers = p.url, .bus = "auth", .member = "m", .token = "guess"};
    CHECK(dtron_connect(&wrong, &bus, err, sizeof err) == DTRON_ERR_BUS && bus == NULL);
    dtron_options right = {.servers = p.url, .bus = "auth", .member = "m", .token = "t0ken-s3cret"};
    CHECK(dtron_connect(&right, &bus, err, sizeof err) == DTRON_OK && bus != NULL);
    if (bus != NULL) {
        CHECK(dtron_member_count(bus) == 1);
        dtron_close(bus);
    }
    stop_server(&p);
}

/* Runs openssl in folder; exits (skipped, or failed under DTRON_REQUIRE_NATS=1) without it. */
static void openssl(const char *folder, const char *arguments) {
    char command[1024];
    snprintf(command, sizeof command, "cd %s && openssl %s >openssl.log 2>&1", folder, arguments);
    if (system(command) != 0) {
        if (system("command -v openssl >/dev/null 2>&1") != 0) {
            fprintf(stderr, "openssl is not installed%s\n", required() ? ", and DTRON_REQUIRE_NATS=1 requires it"
                                                                        : ": skipped");
            exit(required() ? 1 : 77);
        }
        fprintf(stderr, "openssl %s failed (see %s/openssl.log)\n", arguments, folder);
        failures++;
    }
}

static void test_tls(void) {
    char folder[64] = "/tmp/dtron-c-tls-XXXXXX";
    if (mkdtemp(folder) == NULL) {
        failures++;
        return;
    }
    openssl(folder, "req -x509 -newkey rsa:2048 -nodes -keyout ca.key -out ca.pem -days 1 -subj /CN=dtron-test-ca");
    openssl(folder, "req -x509 -newkey rsa:2048 -nodes -keyout other.key -out other.pem -days 1 -subj /CN=other-ca");
    openssl(folder, "req -newkey rsa:2048 -nodes -keyout server.key -out server.csr -subj /CN=127.0.0.1");
    char san[128], cert[128], key[128], ca[128], other[128];
    snprintf(san, sizeof san, "%s/san.cnf", folder);
    FILE *f = fopen(san, "w");
    if (f != NULL) {
        fputs("subjectAltName=IP:127.0.0.1\n", f);
        fclose(f);
    }
    openssl(folder, "x509 -req -in server.csr -CA ca.pem -CAkey ca.key -CAcreateserial -out server.pem -days 1"
                    " -extfile san.cnf");
    snprintf(cert, sizeof cert, "%s/server.pem", folder);
    snprintf(key, sizeof key, "%s/server.key", folder);
    snprintf(ca, sizeof ca, "%s/ca.pem", folder);
    snprintf(other, sizeof other, "%s/other.pem", folder);
    const char *const extra[] = {"--tls", "--tlscert", cert, "--tlskey", key, NULL};
    nats_server_process p;
    CHECK(start_server(&p, "tls", extra) == 0);
    char err[256] = "";
    dtron_bus *bus = NULL;
    dtron_options untrusted = {.servers = p.url, .bus = "tls", .member = "m", .tls_ca_file = other};
    CHECK(dtron_connect(&untrusted, &bus, err, sizeof err) == DTRON_ERR_BUS && bus == NULL);
    dtron_options trusted = {.servers = p.url, .bus = "tls", .member = "m", .tls_ca_file = ca};
    CHECK(dtron_connect(&trusted, &bus, err, sizeof err) == DTRON_OK && bus != NULL);
    if (bus != NULL) {
        CHECK(dtron_member_count(bus) == 1);
        dtron_close(bus);
    } else {
        fprintf(stderr, "tls: %s\n", err);
    }
    stop_server(&p);
    char command[128];
    snprintf(command, sizeof command, "rm -rf %s", folder);
    if (system(command) != 0) {
        fprintf(stderr, "cannot remove %s\n", folder);
    }
}

int main(void) {
    if (start_server(&plain, "nats", NULL) != 0) {
        fprintf(stderr, "nats-server did not start\n");
        return 1;
    }
    snprintf(url, sizeof url, "%s", plain.url);
    test_order_and_membership();
    test_handshake_clock_and_acknowledgements();
    stop_server(&plain);
    test_token();
    test_tls();
    dtron_shutdown();
    if (failures) {
        fprintf(stderr, "%d checks failed\n", failures);
        return 1;
    }
    printf("all checks passed\n");
    return 0;
}

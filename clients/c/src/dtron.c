/*
 * DTRON's C client on libnats and protobuf-c. The bus is the JetStream stream DTRON_<bus> (subjects dtron.<bus>.>):
 * channel messages on dtron.<bus>.c.<channel> (a Sync, header Dtron-Sender), presence (join, alive every second,
 * leave) on dtron.<bus>.p; every member reads the stream from an ordered consumer, so all see one order. Every
 * message is signed with the bus's secret and every message read is checked before anything else (secret.h).
 */
#define _POSIX_C_SOURCE 200809L
#include "dtron.h"

#include <nats/nats.h>
#include <openssl/crypto.h>
#include <openssl/rand.h>
#include <math.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "Sync.pb-c.h"
#include "secret.h"

#define HEARTBEAT_NS 1000000000LL
#define SILENCE_NS 4000000000LL
#define PING_BURST 8
#define PING_SPACING_NS 20000000LL
#define PING_PERIOD_NS 1000000000LL
#define WINDOW 8
#define PENDING_PINGS 64
#define MAX_MEMBERS 256
#define PUBLISH_WAIT_MS 2000
#define RETRIES 150
#define NAMED_DROPS 1024
#define PRINTABLE 128
/* How long a member waits for its join to come back after the last message it read. */
#define JOIN_WAIT_NS 10000000000LL
/* How far back a member joining a secure bus reads the stream, before the stream's last message (security.md). */
#define HISTORY_NS (2 * DTRON_STALE_NS)
/* how far a tester's reading may lie outside a ping's round trip while the two clocks are still taken as one */
#define SAME_CLOCK_SLACK_NS 1000LL

typedef struct channel {
    char *name;
    char **vars;
    size_t nvars;
    dtron_listener listener;
    void *closure;
    int auto_ack;
    int sending;
    struct channel *next;
} channel;

typedef struct {
    char *name;
    int64_t last_seen;
    uint64_t joined;
} member;

/* A message the stream did not acknowledge, waiting for the timer thread to publish it again. */
typedef struct retry {
    natsMsg *msg;
    int64_t due_ns; /* not before then: a pause between tries, as a server fails over */
    struct retry *next;
} retry;

struct dtron_bus {
    natsConnection *nc;
    jsCtx *js;
    natsSubscription *sub;
    char *bus, *member, *prefix, *presence;
    pthread_mutex_t lock;
    pthread_cond_t joined_cond;
    pthread_t timer;
    int timer_started;
    int closed;
    channel *channels;
    uint64_t sequence;
    member members[MAX_MEMBERS];
    size_t nmembers;
    uint64_t own_join;
    char *tester, *run_tester, *run_id;
    int64_t samples[WINDOW][2];
    size_t nsamples, next_sample;
    int has_estimate;
    int64_t offset_ns, error_ns;
    /* the id of the clock dtron_now_ns reads (the kernel's boot id), "" if unknown; whether a round trip
       contradicted a tester that said it reads the same clock */
    char host_clock[64];
    int same_clock_refuted;
    uint64_t ping_seq[PENDING_PINGS];
    int64_t ping_sent[PENDING_PINGS];
    size_t next_ping_slot;
    int pings_sent;
    int64_t next_ping_ns, next_heartbeat_ns;
    int running;
    int64_t start_tester_ns, unit_us;
    uint64_t generation;
    dtron_stats stats;
    dtron_guard *guard; /* NULL: insecure */
    /* on a secure bus, until this member's join came back: the Dtron-Seq of the join ("" after); the stream's
       messages before it are read only for their senders' numbers (security.md); when one was read last */
    char learning_until[21];
    int64_t last_read_ns;
    /* the messages to publish again (publish_failed adds, the timer thread publishes); their own lock, which the
       library's thread takes, never bus->lock, which a publisher holds while the library may be full */
    pthread_mutex_t retry_lock;
    retry *retries, *retries_tail;
    struct {
        char *sender;
        int reason;
    } named[NAMED_DROPS]; /* the senders and reasons of drops named on standard error */
    size_t nnamed;
};

static void publish_retries(dtron_bus *bus);

int64_t dtron_now_ns(void) {
    struct timespec now;
    clock_gettime(CLOCK_REALTIME, &now);
    return (int64_t)now.tv_sec * 1000000000LL + now.tv_nsec;
}

const char *dtron_strerror(int code) {
    switch (code) {
    case DTRON_OK: return "ok";
    case DTRON_ERR_ARGUMENT: return "bad argument";
    case DTRON_ERR_BUS: return "the bus did not take it";
    case DTRON_ERR_CLOSED: return "closed";
    case DTRON_ERR_DUPLICATE: return "acknowledged before";
    case DTRON_ERR_KEY: return "the key file cannot be used";
    default: return "unknown error";
    }
}

static void warn(const dtron_bus *bus, const char *format, ...) {
    va_list args;
    va_start(args, format);
    fprintf(stderr, "dtron %s: ", bus->member);
    vfprintf(stderr, format, args);
    fputc('\n', stderr);
    va_end(args);
}

static char *copy(const char *text) {
    return text == NULL ? NULL : strdup(text);
}

static void replace(char **field, const char *text) {
    free(*field);
    *field = copy(text);
}

static int is_identifier(const char *name) {
    if (name == NULL || !(*name == '_' || (*name >= 'A' && *name <= 'Z') || (*name >= 'a' && *name <= 'z'))) {
        return 0;
    }
    for (const char *c = name; *c; c++) {
        if (!(*c == '_' || (*c >= 'A' && *c <= 'Z') || (*c >= 'a' && *c <= 'z') || (*c >= '0' && *c <= '9'))) {
            return 0;
        }
    }
    return 1;
}

static int is_control(const char *name) {
    return strcmp(name, "dtron_hello") == 0 || strcmp(name, "dtron_ping") == 0 || strcmp(name, "dtron_pong") == 0
           || strcmp(name, "dtron_serve") == 0 || strcmp(name, "dtron_ack") == 0;
}

static int is_run_channel(const char *name) {
    return strcmp(name, DTRON_RUN_START) == 0 || strcmp(name, DTRON_RUN_STOP) == 0;
}

static int is_reserved(const char *name) {
    return is_control(name) || is_run_channel(name) || strcmp(name, "dtron_verdict") == 0
           || strcmp(name, "dtron_model") == 0 || strcmp(name, "dtron_model_outcome") == 0
           || strcmp(name, "dtron_alarm") == 0;
}

/* ---- channels (lock held) ---- */

static channel *find_channel(dtron_bus *bus, const char *name) {
    for (channel *c = bus->channels; c; c = c->next) {
        if (strcmp(c->name, name) == 0) {
            return c;
        }
    }
    return NULL;
}

static int same_template(const channel *c, const char *const *vars, size_t nvars) {
    if (c->nvars != nvars) {
        return 0;
    }
    for (size_t i = 0; i < nvars; i++) {
        if (strcmp(c->vars[i], vars[i]) != 0) {
            return 0;
        }
    }
    return 1;
}

/* Finds or adds a channel with this template; NULL if it has another template or bad names. */
static channel *template_of(dtron_bus *bus, const char *name, const char *const *vars, size_t nvars) {
    if (!is_identifier(name)) {
        return NULL;
    }
    for (size_t i = 0; i < nvars; i++) {
        if (!is_identifier(vars[i])) {
            return NULL;
        }
        for (size_t j = 0; j < i; j++) {
            if (strcmp(vars[i], vars[j]) == 0) {
                return NULL;
            }
        }
    }
    channel *c = find_channel(bus, name);
    if (c != NULL) {
        return same_template(c, vars, nvars) ? c : NULL;
    }
    c = calloc(1, sizeof *c);
    c->name = copy(name);
    c->vars = calloc(nvars ? nvars : 1, sizeof *c->vars);
    for (size_t i = 0; i < nvars; i++) {
        c->vars[i] = copy(vars[i]);
    }
    c->nvars = nvars;
    c->next = bus->channels;
    bus->channels = c;
    return c;
}

/* ---- publishing (lock held, so that sequence numbers and the connection's order agree) ---- */

static int publish(dtron_bus *bus, const char *subject, const char *presence, const uint8_t *data, size_t len) {
    natsMsg *msg = NULL;
    char id[200], joined[32];
    const char *joined_header = NULL;
    if (natsMsg_Create(&msg, subject, NULL, (const char *)data, (int)len) != NATS_OK) {
        return DTRON_ERR_BUS;
    }
    /* an id no one can tell in advance: no other process can publish first under it and have the stream drop
       this message as the duplicate */
    unsigned char random[16];
    if (RAND_bytes(random, sizeof random) != 1) {
        natsMsg_Destroy(msg);
        return DTRON_ERR_BUS;
    }
    int at = snprintf(id, sizeof id, "%.150s-", bus->member);
    for (size_t i = 0; i < sizeof random; i++) {
        at += snprintf(id + at, sizeof id - (size_t)at, "%02x", random[i]);
    }
    natsMsgHeader_Set(msg, "Dtron-Sender", bus->member);
    natsMsgHeader_Set(msg, "Nats-Msg-Id", id);
    if (presence != NULL) {
        natsMsgHeader_Set(msg, "Dtron-Presence", presence);
        if (strcmp(presence, "alive") == 0 && bus->own_join > 0) {
            snprintf(joined, sizeof joined, "%llu", (unsigned long long)bus->own_join);
            natsMsgHeader_Set(msg, "Dtron-Joined", joined);
            joined_header = joined;
        }
    }
    if (bus->guard != NULL) { /* signed once: publish_failed publishes the same message again */
        char seq[24], sent_at[24], code[65];
        dtron_guard_sign(bus->guard, subject, bus->member, presence, joined_header, data, len, dtron_now_ns(), seq,
                         sent_at, code);
        natsMsgHeader_Set(msg, "Dtron-Seq", seq);
        natsMsgHeader_Set(msg, "Dtron-Time", sent_at);
        natsMsgHeader_Set(msg, "Dtron-Mac", code);
    }
    jsPubOptions options;
    jsPubOptions_Init(&options);
    options.MaxWait = PUBLISH_WAIT_MS; /* no acknowledgement by then: publish_failed publishes it again */
    natsStatus status = js_PublishMsgAsync(bus->js, &msg, &options);
    if (status != NATS_OK) {
        natsMsg_Destroy(msg);
        return DTRON_ERR_BUS;
    }
    return DTRON_OK;
}

static int publish_presence(dtron_bus *bus, const char *what) {
    return publish(bus, bus->presence, what, NULL, 0);
}

/* Stamps, encodes and publishes a Sync on a channel. */
static int publish_sync(dtron_bus *bus, const char *name, const dtron_var *vars, size_t nvars, int64_t event_ns,
                        const char *acked_sender, uint64_t acked_sequence, uint64_t *sequence_out) {
    Dtron__Sync sync = DTRON__SYNC__INIT;
    Dtron__Variable variables[64];
    Dtron__Variable *pointers[64];
    char **receives = NULL, **sends = NULL;
    size_t nreceives = 0, nsends = 0;
    int64_t now = dtron_now_ns();
    if (nvars > 64) {
        return DTRON_ERR_ARGUMENT;
    }
    for (size_t i = 0; i < nvars; i++) {
        dtron__variable__init(&variables[i]);
        variables[i].name = (char *)vars[i].name;
        variables[i].value = vars[i].value;
        pointers[i] = &variables[i];
    }
    sync.name = (char *)name;
    sync.n_variables = nvars;
    sync.variables = pointers;
    sync.sender = bus->member;
    sync.sequence = ++bus->sequence;
    sync.publish_time_ns = now;
    sync.event_time_ns = event_ns == 0 || event_ns == now ? 0 : event_ns;
    sync.run_id = bus->run_id ? bus->run_id : "";
    sync.acked_sender = (char *)(acked_sender ? acked_sender : "");
    sync.acked_sequence = acked_sequence;
    if (bus->has_estimate) {
        sync.clock_offset_ns = bus->offset_ns;
        sync.clock_error_ns = bus->error_ns;
    }
    if (strcmp(name, "dtron_serve") == 0) {
        size_t count = 0;
        for (channel *c = bus->channels; c; c = c->next) {
            count++;
        }
        receives = calloc(count + 1, sizeof *receives);
        sends = calloc(count + 1, sizeof *sends);
        for (channel *c = bus->channels; c; c = c->next) {
            if (!is_reserved(c->name) && c->listener) {
                receives[nreceives++] = c->name;
            }
            if (!is_reserved(c->name) && c->sending) {
                sends[nsends++] = c->name;
            }
        }
        sync.n_receives = nreceives;
        sync.receives = receives;
        sync.n_sends = nsends;
        sync.sends = sends;
    }
    if (strcmp(name, "dtron_ping") == 0) {
        bus->ping_seq[bus->next_ping_slot] = sync.sequence;
        bus->ping_sent[bus->next_ping_slot] = now;
        bus->next_ping_slot = (bus->next_ping_slot + 1) % PENDING_PINGS;
    }
    size_t len = dtron__sync__get_packed_size(&sync);
    uint8_t *buffer = malloc(len ? len : 1);
    dtron__sync__pack(&sync, buffer);
    char subject[512];
    snprintf(subject, sizeof subject, "%s%s", bus->prefix, name);
    int result = publish(bus, subject, NULL, buffer, len);
    free(buffer);
    free(receives);
    free(sends);
    if (sequence_out) {
        *sequence_out = sync.sequence;
    }
    return result;
}

static void announce(dtron_bus *bus) {
    if (!bus->closed) {
        publish_sync(bus, "dtron_serve", NULL, 0, 0, NULL, 0, NULL);
    }
}

/* The id of the wall clock dtron_now_ns reads: "linux-boot:" and the kernel's boot id (members with equal ids read
   one and the same CLOCK_REALTIME), or "" where it cannot be read. */
static void read_host_clock(char *out, size_t size) {
    char id[48] = "";
    out[0] = '\0';
    FILE *f = fopen("/proc/sys/kernel/random/boot_id", "r");
    if (f == NULL) {
        return;
    }
    if (fgets(id, sizeof id, f) != NULL) {
        id[strcspn(id, "\r\n")] = '\0';
        if (id[0] != '\0') {
            snprintf(out, size, "linux-boot:%s", id);
        }
    }
    fclose(f);
}

/* ---- membership and the tester (lock held) ---- */

static void forget_tester(dtron_bus *bus) {
    replace(&bus->tester, NULL);
    replace(&bus->run_tester, NULL);
    replace(&bus->run_id, NULL);
    bus->nsamples = 0;
    bus->has_estimate = 0;
    bus->same_clock_refuted = 0;
    bus->running = 0;
}

static void learn_tester(dtron_bus *bus, const char *tester) {
    if (bus->tester && strcmp(bus->tester, tester) == 0) {
        return;
    }
    replace(&bus->tester, tester);
    bus->nsamples = 0;
    bus->has_estimate = 0;
    bus->same_clock_refuted = 0;
    bus->pings_sent = 0;
    bus->next_ping_ns = 0; /* at once */
}

static long member_index(dtron_bus *bus, const char *name) {
    for (size_t i = 0; i < bus->nmembers; i++) {
        if (strcmp(bus->members[i].name, name) == 0) {
            return (long)i;
        }
    }
    return -1;
}

static void remove_member(dtron_bus *bus, size_t i) {
    if (bus->tester && strcmp(bus->tester, bus->members[i].name) == 0) {
        forget_tester(bus);
    }
    free(bus->members[i].name);
    memmove(&bus->members[i], &bus->members[i + 1], (bus->nmembers - i - 1) * sizeof bus->members[0]);
    bus->nmembers--;
}

static void membership(dtron_bus *bus, uint64_t sequence, int64_t stream_ns, const char *sender,
                       const char *presence, const char *joined_header) {
    int was_member = member_index(bus, bus->member) >= 0;
    for (size_t i = 0; i < bus->nmembers;) {
        if (bus->members[i].last_seen < stream_ns - SILENCE_NS) {
            remove_member(bus, i);
        } else {
            i++;
        }
    }
    if (sender != NULL) {
        long i = member_index(bus, sender);
        if (i >= 0) {
            bus->members[i].last_seen = stream_ns;
        }
        if (presence != NULL && (strcmp(presence, "join") == 0 || strcmp(presence, "alive") == 0)) {
            uint64_t joined = sequence;
            if (strcmp(presence, "alive") == 0 && joined_header != NULL) {
                joined = strtoull(joined_header, NULL, 10);
            }
            if (i < 0 && bus->nmembers < MAX_MEMBERS) {
                bus->members[bus->nmembers].name = copy(sender);
                bus->members[bus->nmembers].last_seen = stream_ns;
                bus->members[bus->nmembers].joined = joined;
                bus->nmembers++;
            } else if (i >= 0 && strcmp(presence, "join") == 0) {
                bus->members[i].joined = joined;
            }
            if (strcmp(presence, "join") == 0 && strcmp(sender, bus->member) == 0) {
                bus->own_join = sequence;
                pthread_cond_broadcast(&bus->joined_cond);
            } else if (strcmp(presence, "join") == 0 && !bus->closed) {
                publish_presence(bus, "alive"); /* tell the newcomer who is here */
            }
        } else if (presence != NULL && strcmp(presence, "leave") == 0 && i >= 0) {
            remove_member(bus, (size_t)i);
        }
    }
    if (was_member && member_index(bus, bus->member) < 0 && !bus->closed) {
        warn(bus, "silent in the stream for too long; joining again");
        publish_presence(bus, "join");
    }
}

/* ---- receiving ---- */

/* Counts a message the bus's secret drops, and names the first of each sender and reason (lock held). */
/*
 * A sender or subject anyone may choose, fit for one line of standard error: printable ASCII, one '?' for any other
 * character (escape sequences included), at most PRINTABLE characters and "..." when there were more.
 */
static const char *printable(const char *text, char out[PRINTABLE + 4]) {
    const unsigned char *c = (const unsigned char *)(text ? text : "");
    size_t n = 0;
    for (; *c && n < PRINTABLE; c++) {
        if ((*c & 0xC0) != 0x80) { /* a UTF-8 continuation byte belongs to the character that has its '?' */
            out[n++] = *c >= 0x20 && *c < 0x7F ? (char)*c : '?';
        }
    }
    while ((*c & 0xC0) == 0x80) {
        c++;
    }
    strcpy(out + n, *c ? "..." : "");
    return out;
}

static void drop(dtron_bus *bus, const char *subject, const char *anyone, int reason) {
    static const char *const why[] = {"", "no valid code of the bus's secret", "its Dtron-Seq was accepted before",
                                      "its Dtron-Time is more than 120 s away from when the stream stored it"};
    uint64_t *counter = reason == DTRON_DROP_REPLAYED ? &bus->stats.replayed
                        : reason == DTRON_DROP_STALE  ? &bus->stats.stale
                                                      : &bus->stats.unauthenticated;
    (*counter)++;
    char sender[PRINTABLE + 4], where[PRINTABLE + 4];
    printable(anyone, sender);
    for (size_t i = 0; i < bus->nnamed; i++) {
        if (bus->named[i].reason == reason && strcmp(bus->named[i].sender, sender) == 0) {
            return;
        }
    }
    if (bus->nnamed == NAMED_DROPS) {
        return;
    }
    bus->named[bus->nnamed].sender = copy(sender);
    bus->named[bus->nnamed++].reason = reason;
    const char *because = bus->guard ? why[reason] : "it carries a message code, and this member is insecure";
    warn(bus, "dropped a message on %s from '%s', %s: %s (further ones are counted only)", printable(subject, where),
         sender, dtron_drop_reason(reason), because);
}

static void count_rejected(dtron_bus *bus, uint64_t *counter, const char *channel, const char *why) {
    char name[PRINTABLE + 4];
    (*counter)++;
    warn(bus, "rejected a message on channel '%s': %s", printable(channel, name), why);
}

/* Checks a Sync against a template; returns 1 if it fits, else counts it as rejected (lock held). */
static int fits(dtron_bus *bus, const channel *template, const Dtron__Sync *sync, const char *name) {
    if (strcmp(sync->name, name) != 0) {
        count_rejected(bus, &bus->stats.unknown_channel, name, "it names another channel");
        return 0;
    }
    for (size_t i = 0; i < sync->n_variables; i++) {
        const char *variable = sync->variables[i]->name;
        if (variable == NULL || *variable == '\0') {
            count_rejected(bus, &bus->stats.malformed, name, "a variable without a name");
            return 0;
        }
        for (size_t j = 0; j < i; j++) {
            if (strcmp(variable, sync->variables[j]->name) == 0) {
                count_rejected(bus, &bus->stats.malformed, name, "a variable appears twice");
                return 0;
            }
        }
        int known = 0;
        for (size_t k = 0; k < template->nvars; k++) {
            known |= strcmp(template->vars[k], variable) == 0;
        }
        if (!known) {
            count_rejected(bus, &bus->stats.unknown_variables, name, "unknown variable");
            return 0;
        }
    }
    if (sync->n_variables != template->nvars) {
        count_rejected(bus, &bus->stats.missing_variables, name, "missing variables");
        return 0;
    }
    return 1;
}

static void control(dtron_bus *bus, const char *name, const Dtron__Sync *sync, const char *sender, int64_t received) {
    if (strcmp(sender, bus->member) == 0) {
        return;
    }
    if (strcmp(name, "dtron_hello") == 0) {
        if (bus->tester == NULL) {
            learn_tester(bus, sender);
        }
        announce(bus);
    } else if (strcmp(name, "dtron_ping") == 0) {
        /* the tester probes whether this member is there; a live monitor (field probe) asks it as well */
        if ((bus->tester && strcmp(sender, bus->tester) == 0) || sync->probe) {
            publish_sync(bus, "dtron_pong", NULL, 0, received, sender, sync->sequence, NULL);
        }
    } else if (strcmp(name, "dtron_pong") == 0) {
        if (strcmp(sync->acked_sender, bus->member) != 0 || bus->tester == NULL || strcmp(sender, bus->tester) != 0) {
            return;
        }
        for (size_t i = 0; i < PENDING_PINGS; i++) {
            if (bus->ping_seq[i] == sync->acked_sequence && bus->ping_sent[i] != 0) {
                int64_t t0 = bus->ping_sent[i];
                int64_t tester_time = sync->event_time_ns ? sync->event_time_ns : sync->publish_time_ns;
                int64_t round_trip = received - t0;
                bus->ping_sent[i] = 0;
                if (round_trip < 0) {
                    return;
                }
                int64_t a = tester_time - t0, b = tester_time - received;
                int64_t offset = a / 2 + b / 2 + ((a % 2) + (b % 2)) / 2;
                bus->samples[bus->next_sample][0] = offset;
                bus->samples[bus->next_sample][1] = round_trip;
                bus->next_sample = (bus->next_sample + 1) % WINDOW;
                if (bus->nsamples < WINDOW) {
                    bus->nsamples++;
                }
                size_t best = 0;
                for (size_t k = 1; k < bus->nsamples; k++) {
                    if (bus->samples[k][1] < bus->samples[best][1]) {
                        best = k;
                    }
                }
                bus->offset_ns = bus->samples[best][0];
                bus->error_ns = (bus->samples[best][1] + 1) / 2 > 0 ? (bus->samples[best][1] + 1) / 2 : 1;
                /* a tester that reads this member's very clock: offset 0, while every round trip agrees */
                int within = tester_time >= t0 - SAME_CLOCK_SLACK_NS && tester_time <= received + SAME_CLOCK_SLACK_NS;
                bus->same_clock_refuted |= !within;
                if (within && !bus->same_clock_refuted && bus->host_clock[0] != '\0' && sync->host_clock != NULL
                    && strcmp(sync->host_clock, bus->host_clock) == 0) {
                    bus->offset_ns = 0;
                    bus->error_ns = SAME_CLOCK_SLACK_NS;
                }
                bus->has_estimate = 1;
                return;
            }
        }
    }
}

static void on_message(natsConnection *nc, natsSubscription *sub, natsMsg *msg, void *closure) {
    dtron_bus *bus = closure;
    int64_t received = dtron_now_ns();
    const char *subject = natsMsg_GetSubject(msg);
    const char *sender = NULL, *presence = NULL, *joined = NULL;
    const char *seq = NULL, *sent_at = NULL, *mac = NULL;
    jsMsgMetaData *meta = NULL;
    (void)nc;
    (void)sub;
    natsMsgHeader_Get(msg, "Dtron-Sender", &sender);
    natsMsgHeader_Get(msg, "Dtron-Presence", &presence);
    natsMsgHeader_Get(msg, "Dtron-Joined", &joined);
    natsMsgHeader_Get(msg, "Dtron-Seq", &seq);
    natsMsgHeader_Get(msg, "Dtron-Time", &sent_at);
    natsMsgHeader_Get(msg, "Dtron-Mac", &mac);
    pthread_mutex_lock(&bus->lock);
    if (bus->closed) {
        pthread_mutex_unlock(&bus->lock);
        natsMsg_Destroy(msg);
        return;
    }
    if (natsMsg_GetMetaData(&meta, msg) != NATS_OK) {
        char where[PRINTABLE + 4];
        warn(bus, "dropped a message on %s without its stream's metadata", printable(subject, where));
        pthread_mutex_unlock(&bus->lock);
        natsMsg_Destroy(msg);
        return;
    }
    bus->last_read_ns = dtron_now_ns();
    int own_join = bus->learning_until[0] != '\0' && sender != NULL && seq != NULL
                   && strcmp(sender, bus->member) == 0 && strcmp(seq, bus->learning_until) == 0;
    if (bus->guard != NULL && bus->learning_until[0] != '\0' && !own_join) { /* published before this member joined */
        dtron_guard_learn(bus->guard, subject, sender, seq, sent_at, presence, joined, mac, natsMsg_GetData(msg),
                          (size_t)natsMsg_GetDataLength(msg), meta->Timestamp);
        jsMsgMetaData_Destroy(meta);
        pthread_mutex_unlock(&bus->lock);
        natsMsg_Destroy(msg);
        return;
    }
    /* before anything else: an insecure member does not read a secure one's messages, which it cannot check */
    int dropped = bus->guard == NULL
                      ? (mac != NULL ? DTRON_DROP_UNAUTHENTICATED : DTRON_DROP_NONE)
                      : dtron_guard_check(bus->guard, subject, sender, seq, sent_at, presence, joined, mac,
                                          natsMsg_GetData(msg), (size_t)natsMsg_GetDataLength(msg), meta->Timestamp);
    if (own_join && dropped != DTRON_DROP_UNAUTHENTICATED) {
        bus->learning_until[0] = '\0';
    }
    if (dropped != DTRON_DROP_NONE) {
        drop(bus, subject, sender ? sender : "", dropped);
        jsMsgMetaData_Destroy(meta);
        pthread_mutex_unlock(&bus->lock);
        natsMsg_Destroy(msg);
        return;
    }
    int is_presence = strcmp(subject, bus->presence) == 0;
    if (!is_presence) {
        presence = joined = NULL;
    }
    membership(bus, meta->Sequence.Stream, meta->Timestamp, sender, presence, joined);
    jsMsgMetaData_Destroy(meta);
    size_t prefix = strlen(bus->prefix);
    if (is_presence || strncmp(subject, bus->prefix, prefix) != 0) {
        pthread_mutex_unlock(&bus->lock);
        natsMsg_Destroy(msg);
        return;
    }
    const char *name = subject + prefix;
    channel *template = find_channel(bus, name);
    int listened = template != NULL && template->listener != NULL;
    if (!listened && !is_control(name) && !is_run_channel(name)) { /* another member's channel, or a verdict */
        pthread_mutex_unlock(&bus->lock);
        natsMsg_Destroy(msg);
        return;
    }
    Dtron__Sync *sync = dtron__sync__unpack(NULL, (size_t)natsMsg_GetDataLength(msg),
                                            (const uint8_t *)natsMsg_GetData(msg));
    if (sync == NULL || sync->name == NULL || *sync->name == '\0') {
        count_rejected(bus, &bus->stats.malformed, name, "not a Sync message");
        pthread_mutex_unlock(&bus->lock);
        if (sync) {
            dtron__sync__free_unpacked(sync, NULL);
        }
        natsMsg_Destroy(msg);
        return;
    }
    const char *from = *sync->sender ? sync->sender : (sender ? sender : "");
    if (is_control(name)) {
        control(bus, name, sync, from, received);
        pthread_mutex_unlock(&bus->lock);
        dtron__sync__free_unpacked(sync, NULL);
        natsMsg_Destroy(msg);
        return;
    }
    static const char *const timeunit[] = {"timeunit"};
    channel run_template = {.name = (char *)name, .vars = (char **)timeunit,
                            .nvars = strcmp(name, DTRON_RUN_START) == 0 ? 1 : 0};
    int ok = fits(bus, listened ? template : &run_template, sync, name);
    int64_t event = sync->event_time_ns ? sync->event_time_ns : sync->publish_time_ns;
    /* a message of another run (one replayed from an earlier run, say) neither ends this run nor reaches the
       listeners: a stop counts when it comes from this run's tester with this run's id (or none); a message with a
       run id when it is this run's */
    const char *message_run = sync->run_id ? sync->run_id : "";
    int this_run = bus->run_id != NULL && *bus->run_id != '\0' && strcmp(message_run, bus->run_id) == 0;
    if (ok && strcmp(name, DTRON_RUN_STOP) == 0 && !((this_run || *message_run == '\0') && bus->run_tester != NULL
                                                      && strcmp(from, bus->run_tester) == 0)) {
        ok = 0;
    } else if (ok && !is_run_channel(name) && *message_run != '\0' && !this_run) {
        ok = 0;
    }
    if (ok && strcmp(name, DTRON_RUN_START) == 0) {
        replace(&bus->run_tester, from);
        replace(&bus->run_id, sync->run_id);
        if (strcmp(from, bus->member) != 0) {
            learn_tester(bus, from);
        }
        bus->start_tester_ns = event;
        bus->unit_us = sync->n_variables == 1 && sync->variables[0]->value > 0 ? sync->variables[0]->value : 1000;
        bus->generation++;
        bus->running = 1;
    } else if (ok && strcmp(name, DTRON_RUN_STOP) == 0) {
        replace(&bus->run_tester, NULL);
        replace(&bus->run_id, NULL);
        bus->running = 0;
    }
    dtron_listener listener = listened && ok ? template->listener : NULL;
    void *listener_closure = listened ? template->closure : NULL;
    int acknowledge = listened && ok && template->auto_ack && !is_reserved(name) && sync->sequence > 0
                      && bus->run_tester && strcmp(from, bus->run_tester) == 0 && strcmp(from, bus->member) != 0;
    dtron_var vars[64];
    size_t nvars = 0;
    if (listener) {
        bus->stats.accepted++;
        for (size_t k = 0; k < template->nvars; k++) { /* in the template's order */
            for (size_t i = 0; i < sync->n_variables && nvars < 64; i++) {
                if (strcmp(template->vars[k], sync->variables[i]->name) == 0) {
                    vars[nvars].name = template->vars[k];
                    vars[nvars++].value = sync->variables[i]->value;
                }
            }
        }
    }
    pthread_mutex_unlock(&bus->lock);
    if (listener) {
        dtron_message message = {.channel = name, .vars = vars, .nvars = nvars, .sender = from,
                                 .sequence = sync->sequence, .publish_time_ns = sync->publish_time_ns,
                                 .event_time_ns = event, .run_id = sync->run_id,
                                 .clock_offset_ns = sync->clock_offset_ns, .clock_error_ns = sync->clock_error_ns,
                                 .receive_time_ns = received};
        listener(bus, &message, listener_closure);
        if (acknowledge) {
            dtron_acknowledge(bus, &message, 0);
        }
    }
    dtron__sync__free_unpacked(sync, NULL);
    natsMsg_Destroy(msg);
}

/* ---- the timer thread: heartbeats and pings ---- */

static void *timer_main(void *closure) {
    dtron_bus *bus = closure;
    struct timespec step = {0, 5000000};
    for (;;) {
        pthread_mutex_lock(&bus->lock);
        if (bus->closed) {
            pthread_mutex_unlock(&bus->lock);
            return NULL;
        }
        int64_t now = dtron_now_ns();
        if (now >= bus->next_heartbeat_ns) {
            publish_presence(bus, "alive");
            bus->next_heartbeat_ns = now + HEARTBEAT_NS;
        }
        if (bus->tester != NULL && now >= bus->next_ping_ns) {
            publish_sync(bus, "dtron_ping", NULL, 0, 0, NULL, 0, NULL);
            bus->pings_sent++;
            bus->next_ping_ns = now + (bus->pings_sent < PING_BURST ? PING_SPACING_NS : PING_PERIOD_NS);
        }
        pthread_mutex_unlock(&bus->lock);
        publish_retries(bus);
        nanosleep(&step, NULL);
    }
}

/* ---- public API ---- */

static int fail(char *err, size_t errlen, const char *format, const char *detail) {
    if (err && errlen) {
        snprintf(err, errlen, format, detail);
    }
    return DTRON_ERR_BUS;
}

static void free_bus(dtron_bus *bus) {
    if (bus->sub) {
        natsSubscription_Destroy(bus->sub);
    }
    if (bus->js) {
        jsCtx_Destroy(bus->js);
    }
    if (bus->nc) {
        natsConnection_Destroy(bus->nc);
    }
    for (channel *c = bus->channels; c;) {
        channel *next = c->next;
        for (size_t i = 0; i < c->nvars; i++) {
            free(c->vars[i]);
        }
        free(c->vars);
        free(c->name);
        free(c);
        c = next;
    }
    for (size_t i = 0; i < bus->nmembers; i++) {
        free(bus->members[i].name);
    }
    free(bus->bus);
    free(bus->member);
    free(bus->prefix);
    free(bus->presence);
    free(bus->tester);
    free(bus->run_tester);
    free(bus->run_id);
    for (size_t i = 0; i < bus->nnamed; i++) {
        free(bus->named[i].sender);
    }
    dtron_guard_free(bus->guard);
    pthread_mutex_destroy(&bus->lock);
    for (retry *r = bus->retries; r != NULL;) { /* the library's thread is gone: nothing adds any more */
        retry *next = r->next;
        natsMsg_Destroy(r->msg);
        free(r);
        r = next;
    }
    pthread_mutex_destroy(&bus->retry_lock);
    pthread_cond_destroy(&bus->joined_cond);
    free(bus);
}

/* A copy of msg (subject, data and every header), or NULL when it cannot be made. */
static natsMsg *copy_message(natsMsg *msg) {
    natsMsg *copy = NULL;
    if (natsMsg_Create(&copy, natsMsg_GetSubject(msg), NULL, natsMsg_GetData(msg), natsMsg_GetDataLength(msg))
        != NATS_OK) {
        return NULL;
    }
    const char **keys = NULL;
    int nkeys = 0;
    if (natsMsgHeader_Keys(msg, &keys, &nkeys) == NATS_OK) {
        for (int i = 0; i < nkeys; i++) {
            const char **values = NULL;
            int nvalues = 0;
            if (natsMsgHeader_Values(msg, keys[i], &values, &nvalues) == NATS_OK) {
                for (int j = 0; j < nvalues; j++) {
                    natsMsgHeader_Add(copy, keys[i], values[j]);
                }
                free((void *)values);
            }
        }
        free((void *)keys);
    }
    return copy;
}

static void publish_again(dtron_bus *bus, jsPubAckErr *pae);

/* Appends r (its next NULL) to the messages to publish again; from any thread. */
static void enqueue_retry(dtron_bus *bus, retry *r) {
    pthread_mutex_lock(&bus->retry_lock);
    if (bus->retries_tail != NULL) {
        bus->retries_tail->next = r;
    } else {
        bus->retries = r;
    }
    bus->retries_tail = r;
    pthread_mutex_unlock(&bus->retry_lock);
}

/* Publishes the messages waiting to be published again whose pause is over (timer thread, bus->lock not held). */
static void publish_retries(dtron_bus *bus) {
    int64_t now = dtron_now_ns();
    pthread_mutex_lock(&bus->retry_lock);
    retry *r = bus->retries;
    bus->retries = bus->retries_tail = NULL;
    pthread_mutex_unlock(&bus->retry_lock);
    while (r != NULL) {
        retry *next = r->next;
        r->next = NULL;
        if (r->due_ns > now) { /* not yet: back in the queue, in its order */
            enqueue_retry(bus, r);
            r = next;
            continue;
        }
        jsPubOptions options;
        jsPubOptions_Init(&options);
        options.MaxWait = PUBLISH_WAIT_MS;
        natsStatus status = js_PublishMsgAsync(bus->js, &r->msg, &options);
        if (status != NATS_OK) {
            /* not even sent (the library's queue full, the connection gone while it reconnects): no
               acknowledgement will fail for it, so it is counted as a failed try here */
            jsPubAckErr pae;
            memset(&pae, 0, sizeof pae);
            pae.Msg = r->msg;
            pae.Err = status;
            pae.ErrText = natsStatus_GetText(status);
            publish_again(bus, &pae);
        }
        natsMsg_Destroy(r->msg); /* NULL when the library took it */
        free(r);
        r = next;
    }
}

/*
 * The stream did not acknowledge a message (a server failing over, or the library timed out waiting): publish it
 * again, with the same Nats-Msg-Id so that the stream stores it once, until it was tried RETRIES times. Runs on the
 * library's thread, which must not publish (with the library's queue of messages in flight full, that waits for
 * acknowledgements this very thread delivers): a copy goes to the timer thread. Messages refused for good (limits)
 * are reported.
 */
static void publish_failed(jsCtx *js, jsPubAckErr *pae, void *closure) {
    (void)js;
    publish_again(closure, pae);
}

/* Queues a copy of the message of pae for the timer thread, 100 ms from now, unless it was tried enough. */
static void publish_again(dtron_bus *bus, jsPubAckErr *pae) {
    int transient = pae->Err == NATS_TIMEOUT || pae->Err == NATS_NO_RESPONDERS || pae->ErrCode == 503
                    || pae->Err == NATS_CONNECTION_CLOSED || pae->Err == NATS_CONNECTION_DISCONNECTED
                    || pae->Err == NATS_INSUFFICIENT_BUFFER || pae->Err == NATS_STALE_CONNECTION;
    const char *tries_text = NULL;
    int tries = 0;
    if (natsMsgHeader_Get(pae->Msg, "Dtron-Tries", &tries_text) == NATS_OK) {
        tries = atoi(tries_text);
    }
    const char *sent_text = NULL;
    int stale = natsMsgHeader_Get(pae->Msg, "Dtron-Time", &sent_text) == NATS_OK
                && dtron_now_ns() - strtoll(sent_text, NULL, 10) > DTRON_STALE_NS; /* everyone would drop it */
    if (transient && !bus->closed && tries < RETRIES && !stale) {
        natsMsg *again = copy_message(pae->Msg);
        retry *r = again == NULL ? NULL : malloc(sizeof *r);
        if (r != NULL) {
            char next[16];
            snprintf(next, sizeof next, "%d", tries + 1);
            natsMsgHeader_Set(again, "Dtron-Tries", next);
            r->msg = again;
            r->due_ns = dtron_now_ns() + 100000000LL;
            r->next = NULL;
            enqueue_retry(bus, r);
            return;
        }
        natsMsg_Destroy(again);
    }
    warn(bus, "a message was not stored: %s", pae->ErrText ? pae->ErrText : natsStatus_GetText(pae->Err));
}

/*
 * The first of the stream's sequences lo to hi stored at or after from_ns (the stream's clock), found by bisection
 * over the messages' times; a message that cannot be read counts as a later one, so that more is read, not less.
 */
static uint64_t first_since(jsCtx *js, const char *stream, uint64_t lo, uint64_t hi, int64_t from_ns) {
    while (lo < hi) {
        uint64_t mid = lo + (hi - lo) / 2;
        natsMsg *msg = NULL;
        int later = js_GetMsg(&msg, js, stream, mid, NULL, NULL) != NATS_OK || natsMsg_GetTime(msg) >= from_ns;
        natsMsg_Destroy(msg);
        if (later) {
            hi = mid;
        } else {
            lo = mid + 1;
        }
    }
    return lo;
}

int dtron_connect(const dtron_options *options, dtron_bus **out, char *err, size_t errlen) {
    const char *servers = options && options->servers ? options->servers : "nats://127.0.0.1:4222";
    const char *name = options && options->bus ? options->bus : "dtron";
    char generated[64];
    natsOptions *opts = NULL;
    jsErrCode jerr = 0;
    *out = NULL;
    if (strlen(name) == 0 || strlen(name) > 64 || strspn(name, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                                                             "0123456789_-") != strlen(name)) {
        fail(err, errlen, "a NATS bus name is 1 to 64 letters, digits, '_' or '-': '%s'", name);
        return DTRON_ERR_ARGUMENT;
    }
    if (options && options->member) {
        snprintf(generated, sizeof generated, "%s", options->member);
    } else {
        srand((unsigned)(dtron_now_ns() ^ getpid()));
        snprintf(generated, sizeof generated, "dtron-c-%d-%08x", (int)getpid(), (unsigned)rand());
    }
    uint8_t *secret = NULL;
    size_t secret_length = 0;
    if (options && options->insecure) {
        if (options->key_file) {
            fail(err, errlen, "key_file and insecure exclude each other%s", "");
            return DTRON_ERR_ARGUMENT;
        }
        fprintf(stderr, "dtron %s: INSECURE: member %s on bus '%s' neither signs nor checks messages: anyone who can "
                        "reach the NATS servers can speak on this bus and change a verdict\n", generated, generated,
                name);
    } else if (dtron_load_secret(options ? options->key_file : NULL, &secret, &secret_length, err, errlen) != 0) {
        return DTRON_ERR_KEY;
    }
    dtron_bus *bus = calloc(1, sizeof *bus);
    if (secret != NULL) {
        bus->guard = dtron_guard_create(secret, secret_length, (uint64_t)dtron_now_ns());
        OPENSSL_cleanse(secret, secret_length);
        free(secret);
    }
    pthread_mutex_init(&bus->lock, NULL);
    pthread_mutex_init(&bus->retry_lock, NULL);
    pthread_cond_init(&bus->joined_cond, NULL);
    bus->bus = copy(name);
    bus->member = copy(generated);
    read_host_clock(bus->host_clock, sizeof bus->host_clock);
    bus->prefix = malloc(strlen(name) + 16);
    sprintf(bus->prefix, "dtron.%s.c.", name);
    bus->presence = malloc(strlen(name) + 16);
    sprintf(bus->presence, "dtron.%s.p", name);
    bus->members[0].name = copy(generated);
    bus->members[0].last_seen = INT64_MAX / 2;
    bus->nmembers = 1;

    /* the servers, credentials and TLS */
    char *list = copy(servers);
    const char *urls[16];
    int nurls = 0;
    for (char *save = NULL, *url = strtok_r(list, ",", &save); url && nurls < 16; url = strtok_r(NULL, ",", &save)) {
        urls[nurls++] = url;
    }
    natsStatus s = natsOptions_Create(&opts);
    if (s == NATS_OK) s = natsOptions_SetServers(opts, urls, nurls);
    if (s == NATS_OK) s = natsOptions_SetName(opts, bus->member);
    if (s == NATS_OK) s = natsOptions_SetMaxReconnect(opts, -1);
    if (s == NATS_OK) s = natsOptions_SetRetryOnFailedConnect(opts, false, NULL, NULL);
    if (s == NATS_OK && options && options->user) s = natsOptions_SetUserInfo(opts, options->user, options->password);
    if (s == NATS_OK && options && options->token) s = natsOptions_SetToken(opts, options->token);
    if (s == NATS_OK && options && options->creds_file) {
        s = natsOptions_SetUserCredentialsFromFiles(opts, options->creds_file, NULL);
    }
    if (s == NATS_OK && options && options->tls_ca_file) {
        s = natsOptions_SetSecure(opts, true);
        if (s == NATS_OK) s = natsOptions_LoadCATrustedCertificates(opts, options->tls_ca_file);
    }
    if (s == NATS_OK) s = natsConnection_Connect(&bus->nc, opts);
    natsOptions_Destroy(opts);
    free(list);
    if (s != NATS_OK) {
        if (err && errlen) {
            const char *last = nats_GetLastError(NULL);
            snprintf(err, errlen, "cannot connect to NATS servers %s: %s", servers,
                     last && *last ? last : natsStatus_GetText(s));
        }
        free_bus(bus);
        return DTRON_ERR_BUS;
    }

    /* the stream, the ordered consumer, and this member's join */
    jsOptions jsopts;
    jsOptions_Init(&jsopts);
    jsopts.PublishAsync.ErrHandler = publish_failed;
    jsopts.PublishAsync.ErrHandlerClosure = bus;
    char stream[80], subjects[80];
    snprintf(stream, sizeof stream, "DTRON_%s", name);
    snprintf(subjects, sizeof subjects, "dtron.%s.>", name);
    s = natsConnection_JetStream(&bus->js, bus->nc, &jsopts);
    jsStreamInfo *info = NULL;
    uint64_t history_from = 0; /* 0: the stream's first message */
    if (s == NATS_OK) {
        s = js_GetStreamInfo(&info, bus->js, stream, NULL, &jerr);
        if (s == NATS_NOT_FOUND) {
            jsStreamConfig config;
            const char *subject_list[] = {subjects};
            jsStreamConfig_Init(&config);
            config.Name = stream;
            config.Subjects = subject_list;
            config.SubjectsLen = 1;
            config.Storage = js_FileStorage;
            config.Replicas = options && options->replicas > 0 ? options->replicas : 1;
            config.MaxAge = 600LL * 1000000000LL;
            config.MaxBytes = 64LL * 1024 * 1024;
            config.Discard = js_DiscardOld;
            config.Duplicates = 60LL * 1000000000LL;
            s = js_AddStream(&info, bus->js, &config, NULL, &jerr);
            if (s != NATS_OK) { /* created by another member meanwhile */
                s = js_GetStreamInfo(&info, bus->js, stream, NULL, &jerr);
            }
        }
        if (s == NATS_OK && info->State.Msgs > 0) { /* HISTORY_NS before the stream's last message, by its clock */
            history_from = first_since(bus->js, stream, info->State.FirstSeq, info->State.LastSeq,
                                       info->State.LastTime - HISTORY_NS);
        }
        jsStreamInfo_Destroy(info);
    }
    if (s == NATS_OK) {
        jsSubOptions sub_options;
        jsSubOptions_Init(&sub_options);
        sub_options.Ordered = true;
        sub_options.Config.DeliverPolicy = js_DeliverNew;
        if (bus->guard != NULL) { /* so that copies of the messages before the join are known (security.md) */
            snprintf(bus->learning_until, sizeof bus->learning_until, "%llu",
                     (unsigned long long)dtron_guard_next_number(bus->guard));
            /* a start sequence, not a start time: the library makes its ordered consumer anew (a server lost) from
               this configuration with a start sequence, and the server refuses a consumer with both */
            sub_options.Config.DeliverPolicy = history_from > 0 ? js_DeliverByStartSequence : js_DeliverAll;
            sub_options.Config.OptStartSeq = history_from;
        }
        s = js_Subscribe(&bus->sub, bus->js, subjects, on_message, bus, NULL, &sub_options, &jerr);
    }
    if (s != NATS_OK) {
        fail(err, errlen, "JetStream refused the stream or its consumer: %s", natsStatus_GetText(s));
        free_bus(bus);
        return DTRON_ERR_BUS;
    }
    pthread_mutex_lock(&bus->lock);
    publish_presence(bus, "join");
    struct timespec deadline;
    clock_gettime(CLOCK_REALTIME, &deadline);
    deadline.tv_sec += JOIN_WAIT_NS / 1000000000LL;
    while (bus->own_join == 0) {
        if (pthread_cond_timedwait(&bus->joined_cond, &bus->lock, &deadline) != 0) {
            if (bus->learning_until[0] == '\0' || dtron_now_ns() - bus->last_read_ns > JOIN_WAIT_NS) {
                break;
            }
            /* the messages before the join are still coming */
            deadline.tv_sec = (time_t)((bus->last_read_ns + JOIN_WAIT_NS) / 1000000000LL);
            deadline.tv_nsec = (long)((bus->last_read_ns + JOIN_WAIT_NS) % 1000000000LL);
        }
    }
    int joined = bus->own_join != 0;
    bus->next_heartbeat_ns = dtron_now_ns() + HEARTBEAT_NS;
    pthread_mutex_unlock(&bus->lock);
    if (!joined) {
        fail(err, errlen, "this member's join did not come back from stream %s", stream);
        dtron_close(bus);
        return DTRON_ERR_BUS;
    }
    if (pthread_create(&bus->timer, NULL, timer_main, bus) == 0) {
        bus->timer_started = 1;
    }
    *out = bus;
    return DTRON_OK;
}

int dtron_listen(dtron_bus *bus, const char *name, const char *const *vars, size_t nvars, dtron_listener listener,
                 void *closure, int auto_ack) {
    if (bus == NULL || name == NULL || listener == NULL || is_control(name)) {
        return DTRON_ERR_ARGUMENT;
    }
    if ((strcmp(name, DTRON_RUN_START) == 0 && (nvars != 1 || strcmp(vars[0], "timeunit") != 0))
        || (strcmp(name, DTRON_RUN_STOP) == 0 && nvars != 0)) {
        return DTRON_ERR_ARGUMENT;
    }
    pthread_mutex_lock(&bus->lock);
    channel *c = bus->closed ? NULL : template_of(bus, name, vars, nvars);
    if (c == NULL || c->listener != NULL) {
        pthread_mutex_unlock(&bus->lock);
        return bus->closed ? DTRON_ERR_CLOSED : DTRON_ERR_ARGUMENT;
    }
    c->listener = listener;
    c->closure = closure;
    c->auto_ack = auto_ack;
    if (!is_reserved(name)) {
        announce(bus);
    }
    pthread_mutex_unlock(&bus->lock);
    return DTRON_OK;
}

int dtron_declare_output(dtron_bus *bus, const char *name, const char *const *vars, size_t nvars) {
    if (bus == NULL || name == NULL || is_reserved(name)) {
        return DTRON_ERR_ARGUMENT;
    }
    pthread_mutex_lock(&bus->lock);
    channel *c = bus->closed ? NULL : template_of(bus, name, vars, nvars);
    if (c == NULL) {
        pthread_mutex_unlock(&bus->lock);
        return bus->closed ? DTRON_ERR_CLOSED : DTRON_ERR_ARGUMENT;
    }
    if (!c->sending) {
        c->sending = 1;
        announce(bus);
    }
    pthread_mutex_unlock(&bus->lock);
    return DTRON_OK;
}

int dtron_send(dtron_bus *bus, const char *name, const dtron_var *vars, size_t nvars, int64_t event_time_ns) {
    if (bus == NULL || name == NULL || is_control(name) || (nvars > 0 && vars == NULL)) {
        return DTRON_ERR_ARGUMENT;
    }
    pthread_mutex_lock(&bus->lock);
    if (bus->closed) {
        pthread_mutex_unlock(&bus->lock);
        return DTRON_ERR_CLOSED;
    }
    channel *c = find_channel(bus, name);
    int fits_template = c != NULL && c->nvars == nvars;
    for (size_t i = 0; fits_template && i < nvars; i++) {
        int known = 0;
        for (size_t k = 0; k < nvars; k++) {
            known |= vars[i].name != NULL && strcmp(vars[i].name, c->vars[k]) == 0;
        }
        for (size_t j = 0; j < i; j++) {
            known &= strcmp(vars[i].name, vars[j].name) != 0;
        }
        fits_template = known;
    }
    if (!fits_template) {
        pthread_mutex_unlock(&bus->lock);
        return DTRON_ERR_ARGUMENT; /* declare the channel first, and give exactly its variables */
    }
    if (!c->sending && !is_reserved(name)) {
        /* a channel only listened to so far: say that this member sends it before its first message, as
           dtron_declare_output does (a tester ends a run on a message from a member that did not say so) */
        c->sending = 1;
        announce(bus);
    }
    int result = publish_sync(bus, name, vars, nvars, event_time_ns, NULL, 0, NULL);
    if (result == DTRON_OK) {
        bus->stats.published++;
    }
    pthread_mutex_unlock(&bus->lock);
    return result;
}

int dtron_acknowledge(dtron_bus *bus, const dtron_message *message, int64_t applied_at_ns) {
    if (bus == NULL || message == NULL || message->sender == NULL || *message->sender == '\0'
        || message->sequence == 0 || is_reserved(message->channel)) {
        return DTRON_ERR_ARGUMENT;
    }
    pthread_mutex_lock(&bus->lock);
    int result = bus->closed ? DTRON_ERR_CLOSED
                             : publish_sync(bus, "dtron_ack", NULL, 0, applied_at_ns ? applied_at_ns : dtron_now_ns(),
                                            message->sender, message->sequence, NULL);
    pthread_mutex_unlock(&bus->lock);
    return result;
}

void dtron_shutdown(void) {
    nats_CloseAndWait(2000);
}

const char *dtron_member(const dtron_bus *bus) {
    return bus->member;
}

size_t dtron_member_count(dtron_bus *bus) {
    pthread_mutex_lock(&bus->lock);
    size_t count = bus->nmembers;
    pthread_mutex_unlock(&bus->lock);
    return count;
}

int dtron_clock_offset(dtron_bus *bus, int64_t *offset_ns, int64_t *error_ns) {
    pthread_mutex_lock(&bus->lock);
    int has = bus->has_estimate;
    if (offset_ns) *offset_ns = has ? bus->offset_ns : 0;
    if (error_ns) *error_ns = has ? bus->error_ns : 0;
    pthread_mutex_unlock(&bus->lock);
    return has;
}

int dtron_run_running(dtron_bus *bus) {
    pthread_mutex_lock(&bus->lock);
    int running = bus->running;
    pthread_mutex_unlock(&bus->lock);
    return running;
}

uint64_t dtron_run_generation(dtron_bus *bus) {
    pthread_mutex_lock(&bus->lock);
    uint64_t generation = bus->generation;
    pthread_mutex_unlock(&bus->lock);
    return generation;
}

double dtron_run_units_of(dtron_bus *bus, int64_t event_time_ns) {
    pthread_mutex_lock(&bus->lock);
    double units = bus->unit_us <= 0 ? NAN /* no run started yet: no time unit */
                   : (double)(event_time_ns + (bus->has_estimate ? bus->offset_ns : 0) - bus->start_tester_ns)
                         / ((double)bus->unit_us * 1000.0);
    pthread_mutex_unlock(&bus->lock);
    return units;
}

double dtron_run_now_units(dtron_bus *bus) {
    return dtron_run_units_of(bus, dtron_now_ns());
}

int dtron_run_sleep_until(dtron_bus *bus, double units, uint64_t generation) {
    for (;;) {
        pthread_mutex_lock(&bus->lock);
        int current = bus->running && bus->generation == generation && !bus->closed;
        pthread_mutex_unlock(&bus->lock);
        if (!current) {
            return 0;
        }
        double left_units = units - dtron_run_now_units(bus);
        if (left_units <= 0) {
            return 1;
        }
        double left_ns = left_units * (double)bus->unit_us * 1000.0;
        /* wake at least every 5 ms to see a stopped run or a better offset */
        struct timespec step = {0, (long)(left_ns < 5e6 ? left_ns : 5e6)};
        nanosleep(&step, NULL);
    }
}

dtron_stats dtron_get_stats(dtron_bus *bus) {
    pthread_mutex_lock(&bus->lock);
    dtron_stats stats = bus->stats;
    pthread_mutex_unlock(&bus->lock);
    return stats;
}

void dtron_close(dtron_bus *bus) {
    if (bus == NULL) {
        return;
    }
    pthread_mutex_lock(&bus->lock);
    if (!bus->closed) {
        publish_presence(bus, "leave");
    }
    bus->closed = 1;
    pthread_mutex_unlock(&bus->lock);
    if (bus->timer_started) {
        pthread_join(bus->timer, NULL);
    }
    jsPubOptions wait;
    jsPubOptions_Init(&wait);
    wait.MaxWait = 2000;
    js_PublishAsyncComplete(bus->js, &wait);
    if (bus->sub && natsSubscription_Drain(bus->sub) == NATS_OK) {
        natsSubscription_WaitForDrainCompletion(bus->sub, 2000); /* no listener runs any more */
    }
    natsConnection_Close(bus->nc);
    free_bus(bus);
}

/*
 * DTRON's C client: a member of a DTRON bus on NATS JetStream, speaking the protocol of DTRON's Java API (channels
 * with integer variables, the run clock and clock offsets, acknowledgements, the channel-serving handshake).
 *
 * Every member holds the bus's secret: by default the key file ~/.dtron/bus.key ($DTRON_HOME/bus.key when DTRON_HOME
 * is set), which the first member on a machine makes; copy it to the other machines, or name one in key_file. Every
 * message published carries a code made with it, and every message read is checked before anything else: one
 * without a valid code (unauthenticated), one accepted before (replayed) or one whose time is more than 120 s away
 * from when the stream stored it (stale) is dropped, counted, and the first of each sender and reason named on
 * standard error.
 *
 * Thread-safety: every function may be called from any thread. Listeners are called on one receive thread, one
 * message at a time, in the bus's order, without locks held: a listener may send.
 */
#ifndef DTRON_H
#define DTRON_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Results: 0 is success, the others are negative. */
enum {
    DTRON_OK = 0,
    DTRON_ERR_ARGUMENT = -1,  /**< a bad argument: name, variables, or a channel only DTRON sends on */
    DTRON_ERR_BUS = -2,       /**< the NATS servers did not take the message or the connection */
    DTRON_ERR_CLOSED = -3,    /**< the bus is closed */
    DTRON_ERR_DUPLICATE = -4, /**< acknowledged before */
    DTRON_ERR_KEY = -5        /**< the key file cannot be used: missing (when named), empty, or open to others */
};

/** A member of a bus. */
typedef struct dtron_bus dtron_bus;

/** A variable of a message: its name (without the channel prefix) and value. */
typedef struct {
    const char *name;
    int32_t value;
} dtron_var;

/** A message as received (valid only during the listener call) or as sent. Times: ns since the epoch. */
typedef struct {
    const char *channel;
    const dtron_var *vars;
    size_t nvars;
    const char *sender;
    uint64_t sequence;
    int64_t publish_time_ns;
    int64_t event_time_ns;   /**< when the event happened, on the sender's clock */
    const char *run_id;
    int64_t clock_offset_ns; /**< the sender's estimate of (tester's clock - its clock) */
    int64_t clock_error_ns;
    int64_t receive_time_ns;
} dtron_message;

/** A listener: called with each message of its channel. */
typedef void (*dtron_listener)(dtron_bus *bus, const dtron_message *message, void *closure);

/** How to join a bus; zero-initialise and set what is needed. */
typedef struct {
    const char *servers;        /**< nats://HOST:PORT, comma-separated (default nats://127.0.0.1:4222) */
    const char *bus;            /**< the bus name, the tester's --cluster (default "dtron") */
    const char *member;         /**< this member's id (default generated) */
    const char *user;           /**< user name, with password */
    const char *password;
    const char *token;
    const char *creds_file;     /**< NATS credentials file */
    const char *tls_ca_file;    /**< PEM file of certificate authorities: TLS to the servers */
    int replicas;               /**< the stream's replicas if this member creates it (default 1) */
    const char *key_file;       /**< the file with the bus's secret, never made (default: see above, made if missing) */
    int insecure;               /**< 1: neither sign nor check messages (a bus with the original DTRON's adapters);
                                     anyone who reaches the NATS servers can then speak on the bus */
} dtron_options;

/** Counters of a member: published, accepted, and rejected messages by reason. */
typedef struct {
    uint64_t published, accepted, malformed, unknown_channel, unknown_variables, missing_variables;
    uint64_t unauthenticated, replayed, stale; /**< dropped by the bus's secret */
} dtron_stats;

/** The channel on which the tester starts a run, with variable "timeunit" (microseconds per unit). */
#define DTRON_RUN_START "dtron_start"
/** The channel on which the tester ends a run. */
#define DTRON_RUN_STOP "dtron_stop"

/**
 * Joins a bus. On failure returns an error and writes a one-line reason into err (if given); DTRON_ERR_KEY names the
 * key file and why it cannot be used.
 */
int dtron_connect(const dtron_options *options, dtron_bus **bus, char *err, size_t errlen);

/**
 * Calls listener with every message on channel (template: its variable names) from now on. With auto_ack, an input
 * of the current run's tester is acknowledged when the listener returned; else call dtron_acknowledge.
 */
int dtron_listen(dtron_bus *bus, const char *channel, const char *const *vars, size_t nvars, dtron_listener listener,
                 void *closure, int auto_ack);

/** Declares a channel this member sends (a tester's output), so a tester waiting for it knows. */
int dtron_declare_output(dtron_bus *bus, const char *channel, const char *const *vars, size_t nvars);

/**
 * Publishes a message on a declared or listened channel; event_time_ns (0: now) is when its event happened on this
 * host's clock. Returns once the message is handed to the connection, in order. The first message on a channel that
 * was only listened to is preceded by the announcement that this member sends it (as dtron_declare_output makes):
 * a tester ends a run on a message from a member that did not say it sends its channel.
 */
int dtron_send(dtron_bus *bus, const char *channel, const dtron_var *vars, size_t nvars, int64_t event_time_ns);

/** Acknowledges a received input: applied at applied_at_ns (0: now). */
int dtron_acknowledge(dtron_bus *bus, const dtron_message *message, int64_t applied_at_ns);

/** This member's id. */
const char *dtron_member(const dtron_bus *bus);

/** How many members are on the bus now. */
size_t dtron_member_count(dtron_bus *bus);

/** This host's wall clock, ns since the epoch. */
int64_t dtron_now_ns(void);

/** Writes the estimate of (tester's clock - own clock) and its error bound; returns 1 if there is one, else 0. */
int dtron_clock_offset(dtron_bus *bus, int64_t *offset_ns, int64_t *error_ns);

/** Whether a run is under way (between dtron_start and dtron_stop). */
int dtron_run_running(dtron_bus *bus);

/** Counts the runs started; a task of an earlier run can tell that its run is over. */
uint64_t dtron_run_generation(dtron_bus *bus);

/**
 * Run time now, in model time units of the current (or last) run, on the tester's clock; NAN before the first run
 * (there is no time unit yet), as for dtron_run_units_of.
 */
double dtron_run_now_units(dtron_bus *bus);

/** The run time, in units, of an event at event_time_ns on this host's clock; NAN before the first run. */
double dtron_run_units_of(dtron_bus *bus, int64_t event_time_ns);

/** Sleeps until run time units of run generation; returns 1 then, 0 if that run stopped or another started. */
int dtron_run_sleep_until(dtron_bus *bus, double units, uint64_t generation);

/** This member's counters. */
dtron_stats dtron_get_stats(dtron_bus *bus);

/**
 * Says leave, leaves the bus and frees everything, after the listener running now (if any) returned; the bus may not
 * be used afterwards. Not to be called from a listener.
 */
void dtron_close(dtron_bus *bus);

/** Releases what the NATS library keeps for the whole process; call once at exit, after closing every bus. */
void dtron_shutdown(void);

/** A short text for a result code. */
const char *dtron_strerror(int code);

#ifdef __cplusplus
}
#endif

#endif

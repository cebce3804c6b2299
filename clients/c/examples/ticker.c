/*
 * The bundled ticker (models/.../ticker.xml) as a C bus adapter: from time 0 of a run it publishes tick(seq) one
 * period after the previous tick (or the start), numbering the ticks from 1; an input reset restarts the period and
 * the numbering from when it was applied; the run's end stops it. Ticks are scheduled on the run clock (the tester's
 * time). Variant "correct" ticks every 10 time units, "slow" every 13 (a faulty ticker).
 *
 *   dtron-ticker --bus nats://127.0.0.1:4222 --cluster ticker [--variant slow] [--runs 1] [--key-file PATH]
 */
#define _POSIX_C_SOURCE 200809L
#include <dtron.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static const char *const TICK_VARS[] = {"seq"};
static const char *const START_VARS[] = {"timeunit"};

typedef struct {
    pthread_mutex_t lock;
    int period;
    int seq;
    double last;   /* run time of the last tick or reset: the next tick is due a period later */
    unsigned plan; /* changes with every start and reset */
    int stops;
} ticker;

static void restart(ticker *t, double from) {
    pthread_mutex_lock(&t->lock);
    t->seq = 0;
    t->last = from;
    t->plan++;
    pthread_mutex_unlock(&t->lock);
}

static void started(dtron_bus *bus, const dtron_message *message, void *closure) {
    (void)bus;
    (void)message;
    restart(closure, 0.0);
}

/* The tester's reset: acknowledged when this returns, which is when it took effect. */
static void reset(dtron_bus *bus, const dtron_message *message, void *closure) {
    (void)message;
    if (dtron_run_running(bus)) {
        restart(closure, dtron_run_now_units(bus));
    }
}

static void stopped(dtron_bus *bus, const dtron_message *message, void *closure) {
    ticker *t = closure;
    (void)bus;
    (void)message;
    pthread_mutex_lock(&t->lock);
    t->stops++;
    pthread_mutex_unlock(&t->lock);
}

static void pause_ms(long ms) {
    struct timespec step = {0, ms * 1000000L};
    nanosleep(&step, NULL);
}

int main(int argc, char **argv) {
    dtron_options options = {0};
    const char *variant = "correct";
    int runs = 0;
    options.servers = "nats://127.0.0.1:4222";
    for (int i = 1; i + 1 < argc; i += 2) {
        if (strcmp(argv[i], "--bus") == 0) options.servers = argv[i + 1];
        else if (strcmp(argv[i], "--cluster") == 0) options.bus = argv[i + 1];
        else if (strcmp(argv[i], "--variant") == 0) variant = argv[i + 1];
        else if (strcmp(argv[i], "--runs") == 0) runs = atoi(argv[i + 1]);
        else if (strcmp(argv[i], "--key-file") == 0) options.key_file = argv[i + 1]; /* default ~/.dtron/bus.key */
        else {
            fprintf(stderr, "usage: %s [--bus URLS] [--cluster NAME] [--variant correct|slow] [--runs N]"
                            " [--key-file PATH]\n", argv[0]);
            return 1;
        }
    }
    ticker t = {.lock = PTHREAD_MUTEX_INITIALIZER, .period = strcmp(variant, "slow") == 0 ? 13 : 10};
    if (strcmp(variant, "correct") != 0 && strcmp(variant, "slow") != 0) {
        fprintf(stderr, "dtron-ticker: unknown variant '%s' (correct, slow)\n", variant);
        return 1;
    }
    dtron_bus *bus = NULL;
    char err[256];
    if (dtron_connect(&options, &bus, err, sizeof err) != DTRON_OK) {
        fprintf(stderr, "dtron-ticker: %s\n", err);
        return 1;
    }
    dtron_declare_output(bus, "tick", TICK_VARS, 1);
    dtron_listen(bus, DTRON_RUN_START, START_VARS, 1, started, &t, 1);
    dtron_listen(bus, DTRON_RUN_STOP, NULL, 0, stopped, &t, 1);
    dtron_listen(bus, "reset", NULL, 0, reset, &t, 1);
    printf("ticker %s joined bus '%s' as %s\n", variant, options.bus ? options.bus : "dtron", dtron_member(bus));
    fflush(stdout);
    for (;;) {
        pthread_mutex_lock(&t.lock);
        int done = runs > 0 && t.stops >= runs;
        unsigned plan = t.plan;
        double due = t.last + t.period;
        pthread_mutex_unlock(&t.lock);
        if (done) {
            break;
        }
        if (!dtron_run_running(bus) || plan == 0) {
            pause_ms(2);
            continue;
        }
        /* wait for the due time, in short steps so that a reset or the run's end is seen at once */
        int changed = 0;
        while (dtron_run_now_units(bus) < due) {
            pthread_mutex_lock(&t.lock);
            changed = t.plan != plan;
            pthread_mutex_unlock(&t.lock);
            if (changed || !dtron_run_running(bus)) {
                break;
            }
            pause_ms(1);
        }
        if (changed || !dtron_run_running(bus)) {
            continue;
        }
        int64_t ticked_at = dtron_now_ns(); /* the tick happens now; publishing takes a moment more */
        pthread_mutex_lock(&t.lock);
        if (t.plan != plan) {
            pthread_mutex_unlock(&t.lock);
            continue;
        }
        t.seq = (t.seq + 1) % 1000;
        dtron_var seq = {"seq", t.seq};
        t.last = dtron_run_units_of(bus, ticked_at);
        pthread_mutex_unlock(&t.lock);
        int result = dtron_send(bus, "tick", &seq, 1, ticked_at);
        if (result != DTRON_OK) {
            fprintf(stderr, "dtron-ticker: cannot publish tick %d: %s\n", seq.value, dtron_strerror(result));
        }
    }
    dtron_close(bus);
    dtron_shutdown();
    return 0;
}

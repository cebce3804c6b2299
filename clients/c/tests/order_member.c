/*
 * One member of the cross-language total-order test (DTRON's OrderMemberMain in C). Arguments: NATS URL, bus, member
 * id, output file, messages to publish, number of members. Waits until it heard every member say ready (answering
 * newcomers), publishes order(n) for n = 1..messages, records "sender n sequence" of every order message in receive
 * order, writes them to the output file, says finished and waits for everyone's. Exit 0 if it received all messages
 * of all members, 2 if the members did not meet, 3 if messages went missing.
 */
#define _POSIX_C_SOURCE 200809L
#include <dtron.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define MAX_SENDERS 16

static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
static char **lines;
static size_t nlines, capacity;
static char ready[MAX_SENDERS][130], finished[MAX_SENDERS][130];
static int nready, nfinished;
static const char *me;

static void on_order(dtron_bus *bus, const dtron_message *message, void *closure) {
    char line[200];
    (void)bus;
    (void)closure;
    snprintf(line, sizeof line, "%s %d %llu", message->sender, message->vars[0].value,
             (unsigned long long)message->sequence);
    pthread_mutex_lock(&lock);
    if (nlines < capacity) {
        lines[nlines++] = strdup(line);
    }
    pthread_mutex_unlock(&lock);
}

static int add(char list[][130], int *count, const char *sender) {
    for (int i = 0; i < *count; i++) {
        if (strcmp(list[i], sender) == 0) {
            return 0;
        }
    }
    if (*count < MAX_SENDERS) {
        snprintf(list[(*count)++], 130, "%s", sender);
    }
    return 1;
}

static void on_ready(dtron_bus *bus, const dtron_message *message, void *closure) {
    (void)closure;
    pthread_mutex_lock(&lock);
    int added = add(ready, &nready, message->sender);
    pthread_mutex_unlock(&lock);
    if (added && strcmp(message->sender, me) != 0) {
        dtron_send(bus, "ready", NULL, 0, 0); /* answer a newcomer, which may have missed this member's */
    }
}

static void on_finished(dtron_bus *bus, const dtron_message *message, void *closure) {
    (void)bus;
    (void)closure;
    pthread_mutex_lock(&lock);
    add(finished, &nfinished, message->sender);
    pthread_mutex_unlock(&lock);
}

static int wait_for(dtron_bus *bus, int what, size_t target, int seconds) {
    for (int i = 0; i < seconds * 100; i++) {
        pthread_mutex_lock(&lock);
        size_t now = what == 0 ? dtron_member_count(bus) : what == 1 ? (size_t)nready : what == 2 ? nlines
                                                                                   : (size_t)nfinished;
        pthread_mutex_unlock(&lock);
        if (now >= target) {
            return 1;
        }
        struct timespec step = {0, 10000000L};
        nanosleep(&step, NULL);
    }
    return 0;
}

int main(int argc, char **argv) {
    static const char *const order_vars[] = {"n"};
    if (argc != 7) {
        fprintf(stderr, "usage: %s URL BUS MEMBER OUT MESSAGES MEMBERS\n", argv[0]);
        return 1;
    }
    int messages = atoi(argv[5]), members = atoi(argv[6]);
    me = argv[3];
    capacity = (size_t)messages * (size_t)members;
    lines = calloc(capacity, sizeof *lines);
    dtron_options options = {.servers = argv[1], .bus = argv[2], .member = argv[3]};
    dtron_bus *bus = NULL;
    char err[256];
    if (dtron_connect(&options, &bus, err, sizeof err) != DTRON_OK) {
        fprintf(stderr, "%s: %s\n", me, err);
        return 2;
    }
    dtron_listen(bus, "order", order_vars, 1, on_order, NULL, 1);
    dtron_listen(bus, "ready", NULL, 0, on_ready, NULL, 1);
    dtron_listen(bus, "finished", NULL, 0, on_finished, NULL, 1);
    dtron_declare_output(bus, "order", order_vars, 1);
    dtron_declare_output(bus, "ready", NULL, 0);
    dtron_declare_output(bus, "finished", NULL, 0);
    int result = 0;
    if (!wait_for(bus, 0, (size_t)members, 60)) {
        fprintf(stderr, "%s: only %zu members\n", me, dtron_member_count(bus));
        result = 2;
    } else {
        dtron_send(bus, "ready", NULL, 0, 0);
        if (!wait_for(bus, 1, (size_t)members, 60)) {
            fprintf(stderr, "%s: heard only %d members ready\n", me, nready);
            result = 2;
        }
    }
    if (result == 0) {
        for (int n = 1; n <= messages; n++) {
            dtron_var var = {"n", n};
            while (dtron_send(bus, "order", &var, 1, 0) == DTRON_ERR_BUS) { /* too many in flight: wait a moment */
                struct timespec step = {0, 1000000L};
                nanosleep(&step, NULL);
            }
        }
        int complete = wait_for(bus, 2, capacity, 90);
        FILE *out = fopen(argv[4], "w");
        pthread_mutex_lock(&lock);
        for (size_t i = 0; out && i < nlines; i++) {
            fprintf(out, "%s\n", lines[i]);
        }
        pthread_mutex_unlock(&lock);
        if (out) {
            fclose(out);
        }
        dtron_send(bus, "finished", NULL, 0, 0);
        /* the others may take long to catch up (a member that lost its server and reconnected, on a loaded
         * machine): wait for them as long as the tests wait for the slowest member (150 s) */
        int done = wait_for(bus, 3, (size_t)members, 150);
        if (!complete || !done) {
            fprintf(stderr, "%s: received %zu, finished %d\n", me, nlines, nfinished);
            result = 3;
        }
    }
    dtron_close(bus);
    for (size_t i = 0; i < nlines; i++) {
        free(lines[i]);
    }
    free(lines);
    dtron_shutdown();
    return result;
}

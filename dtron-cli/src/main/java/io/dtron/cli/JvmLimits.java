package io.dtron.cli;

import java.io.IOException;
import java.lang.management.ManagementFactory;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Locale;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

/**
 * One-line messages for the JVM's limits, so that running out of heap or stack never reaches the user as a
 * stack trace: a model too large for the heap names the file, the heap limit and the {@code -Xmx} that would
 * load it. Callers print them once the stack that held the model has unwound, so that its memory is garbage.
 */
final class JvmLimits {
    /** Heap the loader needs per MB of model file, with margin (see the loader section of benchmarks.md). */
    static final int HEAP_MB_PER_MODEL_MB = 20;
    /** Heap for DTRON itself, besides the model. */
    private static final long BASE_HEAP_MB = 64;
    private static final long MB = 1 << 20;
    private static final Pattern XMX = Pattern.compile("-Xmx(\\d+)([kKmMgGtT]?)");

    private JvmLimits() {
    }

    /**
     * The heap limit of this JVM in MB: the last {@code -Xmx} it was started with, as the user wrote it (the
     * collector may report a little less), else the limit the JVM chose.
     */
    static long heapLimitMb() {
        long limit = Runtime.getRuntime().maxMemory() / MB;
        for (String arg : ManagementFactory.getRuntimeMXBean().getInputArguments()) {
            Matcher m = XMX.matcher(arg);
            if (m.matches()) {
                long value = Long.parseLong(m.group(1));
                limit = switch (m.group(2).toLowerCase(Locale.ROOT)) {
                    case "t" -> value << 20;
                    case "g" -> value << 10;
                    case "m" -> value;
                    case "k" -> value >> 10;
                    default -> value >> 20;
                };
            }
        }
        return limit;
    }

    /**
     * {@code MODEL: out of memory ...}: the model did not fit in the heap, and the command line of {@code command}
     * with enough heap for it.
     */
    static String modelTooLarge(String command, Path model) {
        long fileMb;
        try {
            fileMb = (Files.size(model) + MB - 1) / MB;
        } catch (IOException e) {
            fileMb = 0;
        }
        long needed = Math.max(BASE_HEAP_MB + HEAP_MB_PER_MODEL_MB * fileMb, 2 * heapLimitMb());
        return model + ": out of memory: loading the model takes more than the Java heap limit of " + heapLimitMb()
                + " MB (about " + HEAP_MB_PER_MODEL_MB + " MB per MB of model); raise the limit, e.g. java -Xmx"
                + size(needed) + " -jar dtron.jar " + command + " " + model + (command.equals("check") ? "" : " ...");
    }

    /** Out of heap outside model loading. */
    static String outOfMemory() {
        return "out of memory: the run needs more than the Java heap limit of " + heapLimitMb()
                + " MB; raise the limit, e.g. java -Xmx" + size(2 * heapLimitMb()) + " -jar dtron.jar ...";
    }

    /** Out of stack: a bug or a construct nested deeper than DTRON expects. */
    static String stackOverflow() {
        return "internal error: stack overflow (something nested too deeply); please report it with the model";
    }

    /** The line for {@code e} when it is one of the JVM's limits, else null. */
    static String describe(Throwable e) {
        if (e instanceof OutOfMemoryError) {
            return outOfMemory();
        }
        return e instanceof StackOverflowError ? stackOverflow() : null;
    }

    /** {@code mb} rounded up to a power of two, in {@code -Xmx} syntax: {@code 512m}, {@code 2g}. */
    private static String size(long mb) {
        long rounded = Long.highestOneBit(Math.max(1, mb - 1)) << 1;
        return rounded >= 1024 ? rounded / 1024 + "g" : rounded + "m";
    }
}

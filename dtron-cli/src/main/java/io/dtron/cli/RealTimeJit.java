package io.dtron.cli;

import java.io.IOException;
import java.lang.management.ManagementFactory;
import java.nio.file.Files;
import java.nio.file.Path;
import javax.management.JMException;
import javax.management.ObjectName;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Keeps the JIT's optimising compiler (C2) out of the JVM of a real-time run: methods are compiled by the quick
 * compiler (C1) alone. In a fresh JVM on a machine of two cores, C2's compilations of the first seconds take a core for
 * milliseconds at a time, and a run whose windows are a few milliseconds wide loses them (at 1 ms per time unit the
 * racing sample passed 8 of 20 runs with C2, 32 of 40 without it in the tester's JVM, 39 of 40 without it in the
 * adapter's JVM too). C1's code is slower, which a run in real time does not feel: it waits for its times.
 *
 * <p>Only a JVM that dtron's own main started ({@link #ownJvm}): an embedding program (a test, the JUnit extension)
 * keeps its compilers. A JVM started with an option of its own about compilation ({@code -XX:TieredStopAtLevel}, {@code
 * -XX:-TieredCompilation}, {@code -XX:CompileCommand}, ...) is left as it is: {@code java -XX:TieredStopAtLevel=4
 * -jar dtron.jar run ...} keeps C2.
 */
final class RealTimeJit {
    private static final Logger LOG = LoggerFactory.getLogger(RealTimeJit.class);
    /** A compiler directive (HotSpot's JSON) that excludes every method from C2; C1 compiles them fully instead. */
    private static final String NO_C2 = "[{match: \"*.*\", c2: {Exclude: true}}]";
    private static boolean own;
    private static boolean done;

    private RealTimeJit() {
    }

    /** Says that dtron's own main started this JVM: a real-time run may then keep C2 out of it. */
    static synchronized void ownJvm() {
        own = true;
    }

    /**
     * Adds the directive once, in a JVM that dtron's main started and that was not started with compilation options
     * of its own; returns whether this JVM compiles with C1 alone from now on (false also where the JVM takes no
     * compiler directives).
     */
    static synchronized boolean compileQuickly() {
        if (done || !own) {
            return done;
        }
        if (ManagementFactory.getRuntimeMXBean().getInputArguments().stream().anyMatch(RealTimeJit::aboutCompiling)) {
            LOG.debug("The JVM was started with options about compiling: C2 is left as they say");
            return false;
        }
        Path directive = null;
        try {
            directive = Files.createTempFile("dtron-no-c2", ".json");
            Files.writeString(directive, NO_C2);
            ManagementFactory.getPlatformMBeanServer().invoke(
                    new ObjectName("com.sun.management:type=DiagnosticCommand"), "compilerDirectivesAdd",
                    new Object[] {new String[] {directive.toString()}}, new String[] {String[].class.getName()});
            done = true;
            LOG.debug("Compiling with C1 alone for the real-time run");
        } catch (IOException | JMException | RuntimeException e) {
            LOG.debug("C2 stays: the JVM took no compiler directive ({})", e.toString());
        } finally {
            if (directive != null) {
                try {
                    Files.deleteIfExists(directive);
                } catch (IOException e) {
                    LOG.debug("Could not delete {}", directive);
                }
            }
        }
        return done;
    }

    private static boolean aboutCompiling(String jvmArgument) {
        return jvmArgument.startsWith("-XX:TieredStopAtLevel") || jvmArgument.contains("TieredCompilation")
                || jvmArgument.startsWith("-XX:CompileCommand") || jvmArgument.startsWith("-XX:CompilerDirectives")
                || jvmArgument.equals("-Xint") || jvmArgument.equals("-Xcomp");
    }
}

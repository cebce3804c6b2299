package io.dtron.cli;

import java.lang.management.ManagementFactory;
import javax.management.ObjectName;

/**
 * A JVM for {@link RealTimeJitTest}: says that dtron's main started it when its first argument is {@code own}, asks
 * {@link RealTimeJit#compileQuickly()} as a real-time run does, and prints what it answered and the JVM's compiler
 * directives ({@code jcmd PID Compiler.directives_print}).
 */
final class RealTimeJitProbe {
    private RealTimeJitProbe() {
    }

    public static void main(String[] args) throws Exception {
        if (args.length > 0 && args[0].equals("own")) {
            RealTimeJit.ownJvm();
        }
        System.out.println("compiles quickly: " + RealTimeJit.compileQuickly());
        System.out.println(ManagementFactory.getPlatformMBeanServer().invoke(
                new ObjectName("com.sun.management:type=DiagnosticCommand"), "compilerDirectivesPrint",
                new Object[] {new String[0]}, new String[] {String[].class.getName()}));
    }
}

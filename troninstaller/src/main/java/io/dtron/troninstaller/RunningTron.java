package io.dtron.troninstaller;

import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.io.OutputStream;
import java.nio.charset.Charset;
import java.time.Duration;
import org.apache.commons.exec.CommandLine;
import org.apache.commons.exec.DefaultExecuteResultHandler;
import org.apache.commons.exec.ExecuteWatchdog;
import org.apache.commons.exec.Executor;

/** A TRON process started by {@link TronLauncher}: its output so far, its end, and a way to stop it. */
public final class RunningTron implements AutoCloseable {
    private final CommandLine command;
    private final Output output;
    private final ExecuteWatchdog watchdog;
    private final DefaultExecuteResultHandler result;

    RunningTron(CommandLine command, Output output, ExecuteWatchdog watchdog, DefaultExecuteResultHandler result) {
        this.command = command;
        this.output = output;
        this.watchdog = watchdog;
        this.result = result;
    }

    /** Whether TRON still runs. */
    public boolean isRunning() {
        return !result.hasResult();
    }

    /**
     * Waits for TRON to end and returns its exit code.
     *
     * @throws IOException when TRON could not be run, or still runs after {@code timeout} (it is then ended)
     */
    public int waitFor(Duration timeout) throws IOException, InterruptedException {
        result.waitFor(timeout);
        if (!result.hasResult()) {
            close();
            throw new IOException(String.join(" ", command.toStrings()) + " still ran after " + timeout.toSeconds()
                    + " s and was ended");
        }
        if (watchdog.killedProcess()) {
            throw new IOException(String.join(" ", command.toStrings()) + " ran past its time limit and was ended");
        }
        if (result.getException() != null && result.getExitValue() == Executor.INVALID_EXITVALUE) {
            throw new IOException("cannot run " + String.join(" ", command.toStrings()) + ": "
                    + result.getException().getMessage(), result.getException());
        }
        return result.getExitValue();
    }

    /** Everything TRON printed so far, standard output and error interleaved. */
    public String output() {
        return output.text();
    }

    /** Ends TRON if it still runs. */
    @Override
    public void close() {
        if (isRunning()) {
            watchdog.destroyProcess();
        }
    }

    /** Collects TRON's output and echoes it. */
    static final class Output extends OutputStream {
        private final ByteArrayOutputStream buffer = new ByteArrayOutputStream();
        private final OutputStream echo;

        Output(OutputStream echo) {
            this.echo = echo;
        }

        @Override
        public synchronized void write(int b) throws IOException {
            buffer.write(b);
            if (echo != null) {
                echo.write(b);
            }
        }

        @Override
        public synchronized void write(byte[] b, int off, int len) throws IOException {
            buffer.write(b, off, len);
            if (echo != null) {
                echo.write(b, off, len);
                echo.flush();
            }
        }

        synchronized String text() {
            return buffer.toString(Charset.defaultCharset());
        }
    }
}
